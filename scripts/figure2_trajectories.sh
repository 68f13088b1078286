#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The report's Figure 2 experiment as trajectories: the elastic ball drop over 20 s and the elastic
# block at rest on a 20 degree incline over 5 s, each under the Guendelman order and under the
# traditional order, written to docs/figures/ (every 10th step). Builds impulse first if needed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
impulse="${IMPULSE:-$root/build/impulse}"
[ -x "$impulse" ] || "$root/scripts/build.sh"
out="$root/docs/figures"
mkdir -p "$out"
for scheme in guendelman traditional; do
  "$impulse" run "$root/scenes/ball_drop_elastic.json" --scheme "$scheme" --every 10 \
    --out "$out/ball_drop_elastic_$scheme.csv" > /dev/null
  "$impulse" run "$root/scenes/incline_rest_elastic.json" --scheme "$scheme" --every 10 \
    --out "$out/incline_rest_elastic_$scheme.csv" > /dev/null
done
echo "wrote $out/{ball_drop_elastic,incline_rest_elastic}_{guendelman,traditional}.csv"
