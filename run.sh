#!/usr/bin/env bash
# Builds the project (installing missing Debian packages) and renders the built-in default scene.
# Usage: ./run.sh [extra options for rasterize]     -> out/default.png, out/default_stats.json
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target rasterize
mkdir -p out
./build/tools/rasterize --output out/default.png --stats out/default_stats.json "$@"
