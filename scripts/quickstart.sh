#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start: install what is needed, build in Release, and simulate the elastic ball drop
# (reference scene 1), writing its trajectory to ball_drop_elastic.csv.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
"$root/build/impulse" run "$root/scenes/ball_drop_elastic.json" --out ball_drop_elastic.csv
