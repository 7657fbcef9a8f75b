#!/usr/bin/env bash
# Builds the fuzzers with clang, AddressSanitizer and UndefinedBehaviorSanitizer (in build-fuzz/)
# and runs each for a fixed time: fuzz/run.sh [seconds per fuzzer, default 20] [fuzzer names...].
# Each starts from its seed corpus fuzz/corpus/<name>/ (kept small, in the repository) plus what
# earlier runs found (build-fuzz/corpus/<name>/, not in the repository). A crash, a sanitizer
# report, a timeout (-timeout, seconds per input) or running out of memory stops the run with a
# non-zero status; the input that did it is left in build-fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
shift || true
jobs="$(nproc)"

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
      -DCMAKE_CXX_COMPILER=clang++ -DRASTER_BUILD_FUZZERS=ON -DRASTER_SANITIZE=ON \
      -DRASTER_BUILD_TESTS=OFF -DRASTER_BUILD_BENCHMARKS=OFF >/dev/null
fuzzers=("$@")
if [ ${#fuzzers[@]} -eq 0 ]; then
  for source in fuzz/*_fuzzer.cpp; do fuzzers+=("$(basename "$source" .cpp)"); done
fi
cmake --build build-fuzz -j"$jobs" --target "${fuzzers[@]}"

mkdir -p build-fuzz/artifacts
for fuzzer in "${fuzzers[@]}"; do
  name="${fuzzer%_fuzzer}"
  mkdir -p "build-fuzz/corpus/$name" "fuzz/corpus/$name"
  options=()
  [ -f "fuzz/$name.dict" ] && options+=("-dict=fuzz/$name.dict")
  echo "fuzz: $fuzzer for ${seconds} s" >&2
  # The log keeps libFuzzer's progress lines out of CI output unless something went wrong.
  log="build-fuzz/$fuzzer.log"
  if ! "build-fuzz/fuzz/$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/ "${options[@]}" \
      "build-fuzz/corpus/$name" "fuzz/corpus/$name" >"$log" 2>&1; then
    tail -n 60 "$log" >&2
    echo "fuzz: $fuzzer FAILED (log: $log, input: build-fuzz/artifacts/)" >&2
    exit 1
  fi
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
  echo "fuzz: $fuzzer ok, $runs inputs in ${seconds} s ($((runs / seconds)) per second)" >&2
done
