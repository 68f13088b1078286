#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Prints the oracle figures of reference scenes 1-8 (shared scenarios) from `impulse run` trajectories.

    python3 scripts/oracle_figures.py [--impulse build/impulse] [--dt 0.001]

The tests assert these figures; this script only measures and prints them.
"""
import argparse
import csv
import math
import pathlib
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(impulse, scene, dt, out):
    subprocess.run([impulse, "run", str(ROOT / "scenes" / f"{scene}.json"), "--dt", str(dt), "--out", out],
                   check=True, stdout=subprocess.DEVNULL)
    rows = list(csv.DictReader(open(out)))
    bodies = {}
    for r in rows:
        bodies.setdefault(int(r["body"]), []).append({k: float(v) for k, v in r.items()})
    return bodies


def apexes(samples):
    found = []
    for a, b in zip(samples, samples[1:]):
        if a["vz"] > 0 >= b["vz"]:
            found.append(max(a["z"], b["z"]))
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--impulse", default=str(ROOT / "build" / "impulse"))
    parser.add_argument("--dt", type=float, default=0.001)
    args = parser.parse_args()
    tmp = tempfile.mkdtemp()
    out = f"{tmp}/t.csv"
    dt = args.dt

    b = run(args.impulse, "ball_drop_elastic", dt, out)[0]
    a = apexes(b)
    print(f"1 ball_drop_elastic  {len(a)} apexes, largest relative error {max(abs(x - 2.0) for x in a) / 2.0:.1e} "
          f"(oracle 1e-3), deepest penetration {max(0.0, 0.1 - min(s['z'] for s in b)) / 0.1 * 100:.3f} % of r")

    b = run(args.impulse, "ball_drop_damped", dt, out)[0]
    a = apexes(b)
    errors = [abs(a[k - 1] - (0.1 + 1.9 * 0.25 ** k)) / (0.1 + 1.9 * 0.25 ** k) * 100 for k in (1, 2, 3)]
    rest = next(s["t"] for i, s in enumerate(b) if all(abs(q["vz"]) < 1e-6 and abs(q["z"] - 0.1) < 1e-4 for q in b[i:]))
    print(f"2 ball_drop_damped   apex errors k=1..3: {', '.join(f'{e:.3f} %' for e in errors)} (oracle 1 %); "
          f"at rest from t = {rest:.3f} s (oracle <= 1.92 s)")

    for scene, expected in (("ball_ball_headon", ((-1, 0), (1, 0))), ("ball_ball_oblique", ((-0.125, -0.649519), (0.125, 0.649519)))):
        bodies = run(args.impulse, scene, dt, out)
        err = max(math.hypot(bodies[k][-1]["vx"] - expected[k][0], bodies[k][-1]["vy"] - expected[k][1]) for k in (0, 1))
        p = [sum(bodies[k][i]["vx"] for k in (0, 1)) for i in range(len(bodies[0]))]
        print(f"{3 if 'headon' in scene else 4} {scene:18s} final velocity error {err:.2e} m/s; momentum drift {max(abs(x - p[0]) for x in p):.1e}")

    b = run(args.impulse, "spin_friction", dt, out)[0]
    # contact point velocity v + w x (0, 0, -r), r = 0.1
    slip_end = next(s for s in b if math.hypot(s["vx"] - s["wy"] * 0.1, s["vy"] + s["wx"] * 0.1) < 1e-9)
    print(f"5 spin_friction      slip ends at t = {slip_end['t']:.3f} s (oracle 0.1963 s); rolling at "
          f"({slip_end['vx']:.5f}, {slip_end['vy']:.5f}) (oracle (1.42857, -0.08571))")

    for scene, expected in (("incline_stick", 0.0), ("incline_slide", 3.2177)):
        b = run(args.impulse, scene, dt, out)[0]
        d = math.dist((b[0]["x"], b[0]["y"], b[0]["z"]), (b[-1]["x"], b[-1]["y"], b[-1]["z"]))
        label = "displacement after 5 s" if expected == 0.0 else "distance after 2 s"
        print(f"{6 if expected == 0.0 else 7} {scene:18s} {label} {d:.6g} m (oracle {'< 1e-4' if expected == 0.0 else '3.2177 +- 1 %'})")

    bodies = run(args.impulse, "newton_cradle", dt, out)
    rest = max(math.hypot(bodies[k][-1]["vx"], bodies[k][-1]["vy"]) for k in range(5))
    energy = [sum(0.5 * (bodies[k][i]["vx"] ** 2 + bodies[k][i]["vy"] ** 2) for k in range(6)) for i in range(len(bodies[0]))]
    print(f"8 newton_cradle      last ball leaves at {bodies[5][-1]['vx']:.12f} m/s; others at most {rest:.1e} m/s; "
          f"energy drift {max(abs(e - energy[0]) for e in energy):.1e} J")


if __name__ == "__main__":
    main()
