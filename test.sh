#!/usr/bin/env bash
# Builds the project (installing missing Debian packages) and runs every test twice: in the
# Release build, then in a build with AddressSanitizer and UndefinedBehaviorSanitizer; then runs
# each fuzzer briefly (fuzz/run.sh, clang, its own build-fuzz/ folder).
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
jobs="$(nproc)"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

# -O1 without debug info: the sanitizers need no more, and the build takes half the time.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O1 \
      -DRASTER_SANITIZE=ON -DRASTER_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-sanitize -j"$jobs"
ctest --test-dir build-sanitize --output-on-failure -j"$jobs"

# 20 seconds per fuzzer; fuzz/run.sh 600 fuzzes longer by hand.
fuzz/run.sh 20
