#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fails if any C++ source differs from what clang-format makes of it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
files=$(git ls-files '*.cpp' '*.hpp')
if ! clang-format --dry-run --Werror $files; then
  echo "run: clang-format -i \$(git ls-files '*.cpp' '*.hpp')"
  exit 1
fi
