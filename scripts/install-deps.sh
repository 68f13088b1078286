#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian 12 packages impulse builds with. Idempotent: does nothing when all are present.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev        # linear algebra
  nlohmann-json3-dev   # scene files
  libcli11-dev         # command line
  libassimp-dev        # mesh files (OBJ, STL)
  zlib1g-dev           # impulse replay reads gzipped measured trajectories
  libnlopt-dev         # impulse fit: derivative-free optimisation (Subplex)
  libpng-dev           # PNG frames and pictures (impulse render), decoded again by the tests
  gnuplot-nox          # impulse plot draws with gnuplot, headless (pngcairo)
  libjs-three          # three.js and its OrbitControls, inlined into impulse view's page
  ffmpeg               # impulse render joins the frames into an MP4; the tests decode it with ffprobe
  libgtest-dev         # tests
  chromium             # the viewer test loads the page in headless Chromium
  chromium-driver      # ... driven through WebDriver
  python3-selenium     # ... by a Python script
  libbenchmark-dev     # benchmarks
  libbullet-dev        # optional: impulse_bench_bullet runs the same scenes in Bullet 3.24 for comparison
  clang-format         # formatting check
  clang-14             # the fuzz targets (scripts/fuzz.sh) build with clang ...
  libclang-rt-14-dev   # ... and its runtimes: the sanitizers, and libFuzzer as -fsanitize=fuzzer links it
  libfuzzer-14-dev     # ... libFuzzer as a library of its own (libFuzzer.a), for linking by hand
  libmujoco-dev        # optional: MJCF models, impulse compare (impulse_mujoco, MuJoCo 2.2.2)
  python3-dev          # the Python module (import impulse) ...
  pybind11-dev         # ... its bindings
  python3-numpy        # ... body states as arrays
  python3-pytest       # ... its tests
  python3-matplotlib   # ... the example's kinetic-energy plot
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
echo "installing: ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
