#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Drops a small pile of spheres, boxes and capsules into a pen, plots its kinetic energy and reports
the contact forces on the ground at the end.

    PYTHONPATH=build/python python3 examples/python/drop_pile.py --out pile_energy.png
"""
import argparse
import math

import matplotlib

matplotlib.use("Agg")  # no display needed: the plot goes to a PNG
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import impulse  # noqa: E402


def build_pile(count):
    world = impulse.World(gravity=(0.0, 0.0, -9.81))
    wood = world.create_material(restitution=0.3, friction=0.5)
    world.create_body(impulse.Plane(), material=wood, static=True)
    # four walls around the pile, so that what rolls off comes to rest
    for x, y, half in [(0.45, 0, (0.05, 0.5, 0.3)), (-0.45, 0, (0.05, 0.5, 0.3)),
                       (0, 0.45, (0.5, 0.05, 0.3)), (0, -0.45, (0.5, 0.05, 0.3))]:
        world.create_body(impulse.Box(half), material=wood, static=True, position=(x, y, 0.3))
    shapes = [impulse.Sphere(0.1), impulse.Box((0.1, 0.08, 0.06)), impulse.Capsule(0.05, 0.08)]
    for k in range(count):
        # a loose column, each body a little off the axis and turned
        angle = 0.4 * k
        world.create_body(shapes[k % 3], material=wood, density=500.0,
                          position=(0.03 * math.cos(1.7 * k), 0.03 * math.sin(1.3 * k), 0.15 + 0.22 * k),
                          orientation=(math.cos(angle / 2), math.sin(angle / 2), 0.0, 0.0))
    return world


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bodies", type=int, default=30)
    parser.add_argument("--duration", type=float, default=4.0, help="seconds simulated")
    parser.add_argument("--dt", type=float, default=1e-3)
    parser.add_argument("--out", default="pile_energy.png")
    args = parser.parse_args()

    world = build_pile(args.bodies)
    bodies = world.dynamic_bodies()
    steps = round(args.duration / args.dt)
    times = np.empty(steps + 1)
    kinetic = np.empty(steps + 1)
    times[0], kinetic[0] = 0.0, world.kinetic_energy()
    for k in range(1, steps + 1):
        world.step(dt=args.dt)
        times[k], kinetic[k] = world.time, world.kinetic_energy()

    # the contacts of the last step: impulses on body_a (the static ground and walls, bodies 0 to 4,
    # come first in their pairs), divided by dt the forces; at rest they carry the pile's weight
    contacts = world.contacts()
    on_static = contacts["body_a"] < 5
    impulses = contacts["normal_impulses"][on_static, None] * contacts["normals"][on_static]
    impulses += contacts["friction_impulses"][on_static]
    push = -impulses.sum(axis=0) / args.dt
    weight = sum(world.mass(b) for b in bodies) * 9.81
    print(f"{len(contacts['normal_impulses'])} contact points; ground and walls push up with {push[2]:.4g} N "
          f"against a weight of {weight:.4g} N")

    heights = world.positions(bodies)[:, 2]
    speeds = np.linalg.norm(world.linear_velocities(bodies), axis=1)
    print(f"{len(bodies)} bodies, {steps} steps of {args.dt} s")
    print(f"kinetic energy {kinetic.max():.4g} J at most, {kinetic[-1]:.3g} J at the end")
    print(f"pile height {heights.max():.3f} m, fastest body {speeds.max():.3g} m/s")

    figure, axes = plt.subplots(figsize=(7, 4))
    axes.plot(times, kinetic)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("kinetic energy (J)")
    axes.set_yscale("symlog", linthresh=1e-6)
    axes.set_title(f"{len(bodies)} bodies dropped into a pen")
    axes.grid(True, alpha=0.3)
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"plot {args.out}")


if __name__ == "__main__":
    main()
