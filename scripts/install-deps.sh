#!/usr/bin/env bash
# Installs the Debian packages the build needs, only those that are missing.
# Safe to run repeatedly; needs root (or sudo) only when something is missing.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libglm-dev libopenimageio-dev libhwy-dev libtbb-dev
  libcli11-dev nlohmann-json3-dev libtinyobjloader-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # The llvmpipe peer benchmarks (bench/llvmpipe_peer.h): glvnd's EGL and OpenGL headers and
  # libraries, Mesa's EGL vendor library and its DRI drivers (swrast_dri.so holds llvmpipe).
  libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  # The HTML report test opens the report in headless Chromium (tests/report_test.cpp).
  chromium
  # The fuzzers (fuzz/run.sh): clang with libFuzzer and the sanitizer runtimes.
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
