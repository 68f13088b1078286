#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets (tests/fuzz) with clang into build-fuzz/ (or $IMPULSE_FUZZ_BUILD_DIR)
# and runs each for SECONDS (default 60) on a scratch copy of its seeds (tests/fuzz/corpus/TARGET
# and the regression inputs in tests/data/fuzz/TARGET), IMPULSE_FUZZ_JOBS targets at a time
# (default 1). Fails on any crash, sanitizer report, hang, leak or memory blow-up; the input that
# did it is written to build-fuzz/findings/. Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(scene mesh trajectory)
fi
build=${IMPULSE_FUZZ_BUILD_DIR:-$root/build-fuzz}
jobs=${IMPULSE_FUZZ_JOBS:-1}

# Debian's clang 14 (install-deps.sh); -O1 and line tables as in the sanitizer build of .ci/run;
# OpenMP off, one thread per input
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DIMPULSE_FUZZ=ON -DIMPULSE_BUILD_TESTS=OFF \
  -DIMPULSE_BUILD_APP=OFF -DIMPULSE_BUILD_BENCH=OFF -DIMPULSE_BUILD_PYTHON=OFF -DIMPULSE_WITH_MUJOCO=OFF \
  -DIMPULSE_WITH_OPENMP=OFF > /dev/null
executables=()
for target in "${targets[@]}"; do
  executables+=("impulse_${target}_fuzz")
done
cmake --build "$build" --parallel "$(nproc)" --target "${executables[@]}"

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
findings=$build/findings
mkdir -p "$findings"

run() {
  local target=$1
  local corpus=$scratch/$target
  mkdir -p "$corpus"
  cp "$root/tests/fuzz/corpus/$target"/* "$corpus"/
  if [ -d "$root/tests/data/fuzz/$target" ]; then
    cp "$root/tests/data/fuzz/$target"/* "$corpus"/
  fi
  # -timeout: a hang is an input slower than 10 s; -rss_limit_mb also bounds any one allocation;
  # leaks are looked for after every input that allocated more than it freed
  local status=0
  "$build/tests/fuzz/impulse_${target}_fuzz" "$corpus" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -max_len=4096 -artifact_prefix="$findings/$target-" -print_final_stats=1 \
    > "$scratch/$target.log" 2>&1 || status=$?
  echo "$status" > "$scratch/$target.status"
}

running=0
for target in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
  run "$target" &
  running=$((running + 1))
done
wait

failed=0
for target in "${targets[@]}"; do
  log=$scratch/$target.log
  status=$(cat "$scratch/$target.status")
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  last=$(grep -E '^#[0-9]+' "$log" | tail -n 1 | grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+' || true)
  if [ "$status" -eq 0 ]; then
    echo "fuzz $target: ${runs:-0} inputs in ${seconds} s (${rate:-0}/s), ${last:-no coverage line}: no crash, hang or leak"
  else
    echo "fuzz $target: FAILED (libFuzzer exit code $status); its log:"
    grep -vE '^#[0-9]+|^\s*NEW_FUNC|^"' "$log" | tail -n 60
    failed=1
  fi
done
exit "$failed"
