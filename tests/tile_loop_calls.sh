#!/usr/bin/env bash
# The back end's tile loop is meant to be one function per (shader, target) with every per-pixel
# and per-entry helper inlined into it (pipeline/tile_loop.h, "Two builds of the tile loop").
# GCC's inliner gives up inside the largest instantiations without a word: a helper left as a
# call per pixel (interpolateDepth, in W4's depth-only loop) once cost 9 % of a frame. This
# lists the direct calls in every rasterizeTiles / rasterizeTilesAvx2 instantiation of BINARY
# and fails on any callee outside the calls the loop makes on purpose: per tile (the bin's
# entries, the edge tile's lane mask and row copies), per larger triangle and tile (the coverage
# kernel's entry points), on the blend path, and the ones shaders make themselves (texture
# sampling, pipeline/sampler.cpp).
#   tests/tile_loop_calls.sh BINARY...
set -euo pipefail
allowed='TileBins::entries|rast::rectMask|rast::coverTile\(|rast::coverTileFloat|rast::unpackColor|detail::blendFactor|rast::blendAndPack|memcpy@plt|memset@plt|powf@plt|TextureSampler::|lodFromGradients'
for binary in "$@"; do
  calls=$(objdump -d --no-show-raw-insn -C "$binary" | awk '
    /^[0-9a-f]+ <.*>:$/ { inLoop = ($0 ~ /rast::rasterizeTiles(Avx2)?</); next }
    inLoop && /\tcall / && !/call +\*/ { sub(/.*call +[0-9a-f]+ </, ""); sub(/>$/, ""); print }' | sort -u)
  if [ -z "$calls" ]; then
    echo "no rasterizeTiles instantiation found in $binary" >&2
    exit 1
  fi
  unexpected=$(grep -Ev "$allowed" <<< "$calls" || true)
  if [ -n "$unexpected" ]; then
    echo "$binary: calls the tile loop should not make (force the helper inline, RAST_TILE_INLINE):" >&2
    echo "$unexpected" >&2
    exit 1
  fi
  echo "$binary: the tile loop calls only $(grep -Eo "$allowed" <<< "$calls" | sort -u | tr '\n' ' ')"
done
