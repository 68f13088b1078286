#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configures and builds impulse in Release into build/ (or $IMPULSE_BUILD_DIR), extra CMake
# arguments passed through.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${IMPULSE_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" > /dev/null
cmake --build "$build" --parallel "$(nproc)"
