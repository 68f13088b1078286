#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Draws measured against simulated tosses: for each, the height of the centre and the rotation
from the first sample against time, the measurement as points and the simulation as a line.

    plot_tosses.py MEASURED_DIR SIMULATED_DIR OUT.png ID [ID ...]

MEASURED_DIR holds <ID>.csv.gz (or <ID>.csv), SIMULATED_DIR the <ID>.csv that
`impulse replay --out` writes; both in impulse's trajectory format, body 0 plotted."""
import csv
import gzip
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the headless back end is chosen)


def read_trajectory(path):
    """Time, height and orientation (w, x, y, z) of body 0 at every sample."""
    opener = gzip.open if path.suffix == ".gz" else open
    with opener(path, "rt") as f:
        rows = [row for row in csv.DictReader(f) if row["body"] == "0"]
    return ([float(r["t"]) for r in rows], [float(r["z"]) for r in rows],
            [tuple(float(r[k]) for k in ("qw", "qx", "qy", "qz")) for r in rows])


def turned_from_first(orientations):
    """Degrees each orientation is turned from the first: the angle of the relative rotation."""
    first = orientations[0]
    out = []
    for q in orientations:
        dot = abs(sum(a * b for a, b in zip(first, q)))
        norm = math.sqrt(sum(a * a for a in first) * sum(b * b for b in q))
        out.append(math.degrees(2.0 * math.acos(min(1.0, dot / norm))))
    return out


def measured_path(directory, toss):
    for name in (f"{toss}.csv.gz", f"{toss}.csv"):
        if (directory / name).exists():
            return directory / name
    sys.exit(f"plot_tosses.py: {directory}: no measurement {toss}.csv.gz or {toss}.csv")


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    measured_dir, simulated_dir, out = (pathlib.Path(a) for a in sys.argv[1:4])
    tosses = sys.argv[4:]
    figure, axes = plt.subplots(2, len(tosses), figsize=(4 * len(tosses), 6), squeeze=False, sharex="col")
    for column, toss in enumerate(tosses):
        simulated = simulated_dir / f"{toss}.csv"
        if not simulated.exists():
            sys.exit(f"plot_tosses.py: {simulated}: no such simulation (impulse replay --out writes it)")
        mt, mz, mq = read_trajectory(measured_path(measured_dir, toss))
        st, sz, sq = read_trajectory(simulated)
        height, turn = axes[0][column], axes[1][column]
        height.plot(mt, [1000 * z for z in mz], ".", color="black", markersize=3, label="measured")
        height.plot(st, [1000 * z for z in sz], "-", color="tab:red", label="impulse")
        height.set_title(f"toss {toss}")
        turn.plot(mt, turned_from_first(mq), ".", color="black", markersize=3, label="measured")
        turn.plot(st, turned_from_first(sq), "-", color="tab:red", label="impulse")
        turn.set_xlabel("t, s")
        if column == 0:
            height.set_ylabel("height of the centre, mm")
            turn.set_ylabel("turned from the start, degrees")
            height.legend(loc="upper right")
    figure.tight_layout()
    figure.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
