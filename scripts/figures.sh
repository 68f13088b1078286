#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Regenerates the report's pictures in docs/figures/ from the reference scenes: for the elastic
# ball drop (20 s), the spinning ball on the ground, the oblique two-ball collision and the ring
# falling over the peg (a torus mesh: nonconvex contact), a plot
# (height, 3D path, speed and energy against time) and a rendered frame. Builds impulse first if
# needed; needs gnuplot (scripts/install-deps.sh installs it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
impulse="${IMPULSE:-$root/build/impulse}"
[ -x "$impulse" ] || "$root/scripts/build.sh"
out="$root/docs/figures"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# scene, the time of its rendered frame, extra render options
figures=(
  "ball_drop_elastic 0.45 --trail"
  "spin_friction 3.0 --trail"
  "ball_ball_oblique 1.0 --trail"
  "ring_on_peg 3.0 --trail"
)
for figure in "${figures[@]}"; do
  read -r name at extra <<< "$figure"
  scene="$root/scenes/$name.json"
  "$impulse" run "$scene" --every 10 --out "$work/$name.csv" > /dev/null
  "$impulse" plot "$work/$name.csv" --scene "$scene" --out "$out/${name}_plot.png"
  # shellcheck disable=SC2086  # extra holds zero or more options
  "$impulse" render "$work/$name.csv" --scene "$scene" --at "$at" $extra --out "$out/${name}_frame.png"
done
