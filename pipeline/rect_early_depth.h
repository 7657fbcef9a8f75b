// Raster and early depth of a small rectangle of a tile in one pass over its rows.
//
// Most (triangle, tile) entries of a mesh, and all of W2's, meet their tile in a rectangle of a
// few pixels. For those the back end runs one kernel that takes each row of the rectangle from
// coverage through the depth test to the depth write on the same lanes, instead of a coverage
// mask first and then the depth stages with their own passes and bookkeeping (tile_loop.h's
// general path). One source, compiled by Highway for every x86 target and chosen with the
// coverage kernel (rect_early_depth.cpp); the scalar reference kernel has none, and the back end
// then takes the general path for every entry.
#pragma once

#include "pipeline/setup.h"
#include "pipeline/state.h"
#include "rasterizer/coverage.h"
#include "rasterizer/coverage_kernels.h"

namespace rast {

// What the kernel needs of the draw, the same for all its entries.
struct RectDraw {
  FixedPointFormat format;
  CompareOp compare;
  bool depthWrite;
};

struct RectEarlyDepth {
  CoverageMask covered = 0;  // the tile's pixels inside the triangle (and its bounds)
  CoverageMask passed = 0;   // of those, the ones that pass the depth test (Always: all)
};

// For triangle `t`, whose bounds meet tile (tileX, tileY): the tile's pixels inside it, the depth
// test of each against `stored` (the tile's 64 depths, row by row), and, when the draw writes
// depth, the depths of those that pass written over `stored`. Bit for bit what the general path
// gives: the coverage equals coverRect's (rect_early_depth.cpp has the argument), and each depth
// is depthLanes' ((at0 + ddx*dx) + ddy*dy in float, no fused multiply-add, then the clamp to
// [0, 1] that keeps -0 and NaN), compared as depthPasses compares (NaN fails every op but
// NotEqual).
using RectEarlyDepthFn = RectEarlyDepth (*)(const RasterTriangle& t, int tileX, int tileY,
                                            const RectDraw& draw, float* stored);

// The kernel compiled for the same target as `kernel`; null for the scalar reference.
RectEarlyDepthFn rectEarlyDepthFor(const CoverageKernel& kernel);

}  // namespace rast
