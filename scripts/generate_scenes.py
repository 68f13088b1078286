#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the generated reference scenes (stacks, pyramid, stacking regressions, nonconvex scenes) into scenes/.

Run from anywhere: python3 scripts/generate_scenes.py. The hand-written scenes 1-8 are not touched.
"""
import json
import math
import pathlib
import random
import re

SCENES = pathlib.Path(__file__).resolve().parent.parent / "scenes"
GROUND = {"name": "ground", "static": True, "shape": {"type": "plane", "normal": [0, 0, 1], "offset": 0},
          "material": "default"}


def write(name, description, bodies, duration, materials=None, dt=0.001):
    scene = {"name": name, "description": description, "gravity": [0, 0, -9.81], "dt": dt, "duration": duration,
             "materials": materials or {"default": {"restitution": 0.0, "friction": 0.5}}, "bodies": bodies}
    text = json.dumps(scene, indent=2)
    # keep short numeric arrays on one line
    text = re.sub(r"\[\s*([-0-9.e, \n]+?)\s*\]", lambda m: "[" + ", ".join(x.strip() for x in m.group(1).split(",")) + "]", text)
    (SCENES / f"{name}.json").write_text(text + "\n")


def box(name, half, position, mass=None, density=None, static=False, material="default"):
    body = {"name": name}
    if static:
        body["static"] = True
    body["shape"] = {"type": "box", "half_extents": [round(h, 12) for h in half]}
    if mass is not None:
        body["mass"] = mass
    if density is not None:
        body["density"] = density
    body["position"] = [round(p, 12) for p in position]
    body["material"] = material
    return body


def box_stack(n, duration=20.0):
    cubes = [box(f"cube{k}", [0.1] * 3, [0, 0, 0.1 + 0.2 * k], mass=1.0) for k in range(n)]
    write(f"box_stack_{n}", f"Reference scene 9: {n} cubes of side 0.2 stacked exactly on the ground; nothing may move.",
          [GROUND] + cubes, duration)


def pyramid(bottom=20):
    cubes = []
    for row in range(bottom):
        count = bottom - row
        for i in range(count):
            x = (i - (count - 1) / 2) * 0.21
            cubes.append(box(f"r{row}c{i}", [0.1] * 3, [x, 0, 0.1 + 0.2 * row], mass=1.0))
    write("pyramid", f"Reference scene 10: a 2-D pyramid of {len(cubes)} cubes of side 0.2, bottom row of {bottom}, "
          "gaps of 0.01 in a row; it must stand.", [GROUND] + cubes, 10.0)


def heavy_on_light():
    masses = [1, 10, 100, 1, 1000]
    cubes = [box(f"cube{k}_{m}kg", [0.1] * 3, [0, 0, 0.1 + 0.2 * k], mass=float(m)) for k, m in enumerate(masses)]
    write("heavy_on_light", "Five cubes of side 0.2 with masses 1, 10, 100, 1, 1000 kg from the bottom up; the heavy "
          "cubes must not sink through the light ones.", [GROUND] + cubes, 10.0)


def lintel():
    bodies = [GROUND]
    bodies += [box(f"left{k}", [0.1, 0.1, 0.1], [-0.4, 0, 0.1 + 0.2 * k], density=500.0) for k in range(2)]
    bodies += [box(f"right{k}", [0.1, 0.1, 0.05], [0.4, 0, 0.05 + 0.1 * k], density=500.0) for k in range(4)]
    bodies.append(box("lintel", [0.5, 0.1, 0.05], [0, 0, 0.45], density=500.0))
    write("lintel", "A 1.0 x 0.2 x 0.1 lintel across two stacks of equal height: 2 cubes on the left, 4 half-height "
          "boxes on the right. It must stand; breadth-first levels would deadlock here.", bodies, 10.0)


def seesaw():
    bodies = [GROUND,
              box("pivot", [0.05, 0.2, 0.15], [0, 0, 0.15], static=True),
              box("plank", [1.0, 0.15, 0.025], [0, 0, 0.325], mass=10.0),
              box("light", [0.1, 0.1, 0.1], [-0.85, 0, 0.45], mass=5.0),
              box("heavy", [0.1, 0.1, 0.1], [0.85, 0, 1.45], mass=20.0)]
    write("seesaw", "A 10 kg plank on a static pivot, a 5 kg cube at rest on one end and a 20 kg cube dropped from "
          "1 m onto the other: the heavy side goes down and the light cube is thrown up.", bodies, 3.0)


def mesh(name, file, position, orientation=None, mass=None, density=None, static=False, material="default"):
    """A mesh body; position and orientation place the mesh file's own frame."""
    body = {"name": name}
    if static:
        body["static"] = True
    body["shape"] = {"type": "mesh", "file": f"meshes/{file}"}
    if mass is not None:
        body["mass"] = mass
    if density is not None:
        body["density"] = density
    body["position"] = [round(p, 12) for p in position]
    if orientation is not None:
        body["orientation"] = orientation
    body["material"] = material
    return body


def ring_on_peg():
    bodies = [GROUND, mesh("peg", "peg.obj", [0, 0, 0], static=True),
              mesh("ring", "ring.obj", [0.05, 0, 1.0], {"axis": [1, 0, 0], "angle_deg": 30}, mass=1.0)]
    write("ring_on_peg", "Reference scene 13: a torus (hole radius 0.25) tilted 30 degrees falls over a static peg of "
          "radius 0.15; it must end on the ground around the peg, not on its top as its convex hull would.",
          bodies, 3.0)


def tori_stack():
    bodies = [GROUND] + [mesh(f"torus{k}", "torus.obj", [0, 0, 0.05 + 0.1 * k], mass=1.0) for k in range(3)]
    write("tori_stack", "Three tori (centre-line radius 0.2, tube radius 0.05) stacked flat, touching; mesh against "
          "mesh resting contact: they must stand.", bodies, 5.0)


def random_unit_quaternion(rng):
    # uniform over rotations (Shoemake's subgroup algorithm)
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return [round(x, 12) for x in (a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2),
                                    b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3))]


# middle of the bounding box of the meshes whose file origin is not at their middle
FILE_BOX_CENTRES = {"l_block.obj": (0.06, 0.06, 0.03)}


def rotate(q, v):
    """Rotates v by the unit quaternion q = [w, x, y, z]."""
    w, x, y, z = q
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz, v[2] + w * tz + x * ty - y * tx)


def nonconvex_pile(n):
    rng = random.Random(14)
    pieces = ["small_torus.obj", "l_block.obj", "star.obj", "dumbbell.obj", "gear.stl"]
    per_row, spacing = 8, 0.25
    per_layer = per_row * per_row
    layers = (n + per_layer - 1) // per_layer
    top = 0.3 + spacing * (layers - 1)
    height = top + 1.0
    bodies = [GROUND]
    for name, half, centre in (("wall_x_minus", [0.1, 1.2, height / 2], [-1.1, 0, height / 2]),
                               ("wall_x_plus", [0.1, 1.2, height / 2], [1.1, 0, height / 2]),
                               ("wall_y_minus", [1.0, 0.1, height / 2], [0, -1.1, height / 2]),
                               ("wall_y_plus", [1.0, 0.1, height / 2], [0, 1.1, height / 2])):
        bodies.append(box(name, half, centre, static=True))
    for k in range(n):
        layer, slot = divmod(k, per_layer)
        row, column = divmod(slot, per_row)
        position = [(column - (per_row - 1) / 2) * spacing + rng.uniform(-0.02, 0.02),
                    (row - (per_row - 1) / 2) * spacing + rng.uniform(-0.02, 0.02),
                    0.3 + spacing * layer]
        piece = pieces[k % len(pieces)]
        orientation = random_unit_quaternion(rng)
        # the scene places a mesh's file frame: put the middle of each piece's box at the slot
        offset = rotate(orientation, FILE_BOX_CENTRES.get(piece, (0.0, 0.0, 0.0)))
        position = [round(p - o, 12) for p, o in zip(position, offset)]
        bodies.append(mesh(f"piece{k}", piece, position, orientation, density=1000.0))
    write(f"nonconvex_pile_{n}", f"Reference scene 14: {n} nonconvex meshes (tori, L-blocks, stars, dumbbells, gears) "
          "dropped into a 2 m x 2 m box with random orientations; mu = 0.5, eps = 0.3. They must settle without "
          "interpenetrating.", bodies, 10.0, materials={"default": {"restitution": 0.3, "friction": 0.5}})


def read_initial_states(name):
    """Rows of scenes/initial-states/NAME.csv (the t = 0 rows of the trajectory format), by body."""
    rows = (SCENES / "initial-states" / f"{name}.csv").read_text().splitlines()
    header = rows[0].split(",")
    states = [dict(zip(header, (float(x) for x in row.split(",")))) for row in rows[1:] if row]
    return sorted(states, key=lambda state: state["body"])


def pile(kind, n):
    """Reference scenes 11 and 12: a ground plane and four static walls 0.2 thick, inner faces at
    x, y = +-2, from z = 0 to 1 m above the top layer; the bodies start at the shipped states."""
    states = read_initial_states(f"{kind}_pile_{n}")
    height = max(state["z"] for state in states) + 1.0
    bodies = [GROUND]
    for name, half, centre in (("wall_x_minus", [0.1, 2.2, height / 2], [-2.1, 0, height / 2]),
                               ("wall_x_plus", [0.1, 2.2, height / 2], [2.1, 0, height / 2]),
                               ("wall_y_minus", [2.0, 0.1, height / 2], [0, -2.1, height / 2]),
                               ("wall_y_plus", [2.0, 0.1, height / 2], [0, 2.1, height / 2])):
        bodies.append(box(name, half, centre, static=True))
    for state in states:
        k = int(state["body"])
        position = [state["x"], state["y"], state["z"]]
        if kind == "sphere":
            body = {"name": f"ball{k}", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0,
                    "position": position, "material": "default"}
        else:
            body = box(f"cube{k}", [0.1] * 3, position, mass=1.0)
            body["orientation"] = [state["qw"], state["qx"], state["qy"], state["qz"]]
        if any(state[v] != 0.0 for v in ("vx", "vy", "vz")):
            body["velocity"] = [state["vx"], state["vy"], state["vz"]]
        if any(state[w] != 0.0 for w in ("wx", "wy", "wz")):
            body["angular_velocity"] = [state["wx"], state["wy"], state["wz"]]
        bodies.append(body)
    number = 11 if kind == "sphere" else 12
    shape = "spheres of radius 0.1" if kind == "sphere" else "cubes of side 0.2"
    write(f"{kind}_pile_{n}", f"Reference scene {number}: {n} {shape}, m = 1, start at rest at the positions of "
          f"initial-states/{kind}_pile_{n}.csv and fall into a 4 m x 4 m box; mu = 0.5, eps = 0.3. None may escape "
          "the box or end inside another.", bodies, 5.0,
          materials={"default": {"restitution": 0.3, "friction": 0.5}})


if __name__ == "__main__":
    box_stack(10)
    box_stack(50)
    pyramid()
    heavy_on_light()
    lintel()
    seesaw()
    ring_on_peg()
    tori_stack()
    nonconvex_pile(200)
    nonconvex_pile(1000)
    for pile_kind in ("sphere", "box"):
        for pile_size in (1000, 10000):
            pile(pile_kind, pile_size)
