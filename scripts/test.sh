#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install what is needed, build, and run the whole test suite with ctest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
ctest --test-dir "${IMPULSE_BUILD_DIR:-$root/build}" --output-on-failure --parallel "$(nproc)"
