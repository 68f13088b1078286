#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install what is needed, build, and run the whole test suite with ctest. The largest reference
# piles (label "pile": ten thousand spheres or cubes) run on demand:
#   ctest --test-dir build -L pile --output-on-failure
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
ctest --test-dir "${IMPULSE_BUILD_DIR:-$root/build}" --output-on-failure --parallel "$(nproc)" --label-exclude pile
