// Binning's corner tests for a triangle whose bounds lie within 2x2 tiles, made by setup while
// it has the triangle's edges in vector lanes (pipeline/setup_batch.h), so that binning such a
// triangle is a table lookup (TileBins::binTriangles).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "rasterizer/coverage.h"
#include "rasterizer/edge_function.h"
#include "rasterizer/fixed_point.h"
#include "rasterizer/pixel_rect.h"

namespace rast {

// Binning's corner tests of a triangle whose bounds lie within 2x2 tiles (most of a mesh's
// triangles that touch more than one tile), taken where setup has the triangle's edges at hand
// (SetupBatch, clipAndSetup), a batch of triangles at a time in vector lanes, so that binning the
// triangle is a lookup. Bit k, for the tile (tx0 + k % 2, ty0 + k / 2) counted from the bounds'
// first tile (x0 / 8, y0 / 8): the corner test does not reject the tile; bit 4 + k: every sample
// of it is inside and it lies within the bounds (its entry gets kWholeTileBit). Tiles beyond the
// bounds' last tile get bits nobody reads. Exactly binTileRect's decisions: the same exact
// integer values (E at each tile's reach-widened top-left sample, and per edge its least and
// greatest change over a tile), compared the same way.
using SmallTileTests = uint8_t;

// One triangle's tests: its edges' a[e], b[e], c[e] and its bounds. Branch-free, so that setup's
// loop over a batch's lanes vectorises (setup_batch.cpp). Every value fits: the bounds lie in the
// framebuffer (at most 2^15 pixels a side, kMaxFramebufferSide), so the tile corners stay below
// 2^23 subpixels in int32 at either precision; an edge's a and b stay below 2^27 (the guard
// band's span), so each product stays below 2^50 and E at a corner, like c, well inside int64.
[[gnu::always_inline]] inline SmallTileTests smallTileTests(const int32_t (&a)[3],
                                                           const int32_t (&b)[3],
                                                           const int64_t (&c)[3], int32_t x0,
                                                           int32_t y0, int32_t x1, int32_t y1,
                                                           int fractionBits, int32_t reach) {
  const int32_t tx0 = x0 >> kTileShift, ty0 = y0 >> kTileShift;
  const int32_t half = int32_t{1} << (fractionBits - 1);
  // pixelCentreSubpixels of the first tile's first pixel, less the reach (classifyTile's corner).
  const int32_t sx0 = (tx0 * kTileSize) * (int32_t{1} << fractionBits) + half - reach;
  const int32_t sy0 = (ty0 * kTileSize) * (int32_t{1} << fractionBits) + half - reach;
  const int32_t step = kTileSize << fractionBits;
  const int32_t span = ((kTileSize - 1) << fractionBits) + 2 * reach;  // edgeExtent's
  // Per tile k, the OR over the edges of E plus the edge's greatest change over the tile has its
  // sign bit set exactly when some edge is negative at every sample (rejected); with the least
  // change, exactly when some edge is negative at some sample (not inside).
  int64_t rejected[4] = {0, 0, 0, 0}, notInside[4] = {0, 0, 0, 0};
  for (int e = 0; e < 3; ++e) {
    const int64_t stepX = int64_t{a[e]} * step, stepY = int64_t{b[e]} * step;
    const int64_t dx = int64_t{a[e]} * span, dy = int64_t{b[e]} * span;
    const int64_t highest = std::max<int64_t>(dx, 0) + std::max<int64_t>(dy, 0);
    const int64_t lowest = std::min<int64_t>(dx, 0) + std::min<int64_t>(dy, 0);
    const int64_t v0 = int64_t{a[e]} * sx0 + int64_t{b[e]} * sy0 + c[e];
    const int64_t v[4] = {v0, v0 + stepX, v0 + stepY, v0 + stepX + stepY};
    for (int k = 0; k < 4; ++k) {
      rejected[k] |= v[k] + highest;
      notInside[k] |= v[k] + lowest;
    }
  }
  unsigned pass = 0, inside = 0;
  for (int k = 0; k < 4; ++k) {
    pass |= unsigned(rejected[k] >= 0) << k;
    inside |= unsigned(notInside[k] >= 0) << k;
  }
  unsigned within = 0;
  for (int k = 0; k < 4; ++k) {
    const int32_t tx = tx0 + (k & 1), ty = ty0 + (k >> 1);
    within |= unsigned((tx * kTileSize >= x0) & ((tx + 1) * kTileSize <= x1) &
                       (ty * kTileSize >= y0) & ((ty + 1) * kTileSize <= y1))
              << k;
  }
  return SmallTileTests(pass | (inside & within & pass) << 4);
}
inline SmallTileTests smallTileTests(const std::array<EdgeFunction, 3>& edges,
                                     const PixelRect& bounds, FixedPointFormat format,
                                     int32_t reach) {
  const int32_t a[3] = {edges[0].a, edges[1].a, edges[2].a};
  const int32_t b[3] = {edges[0].b, edges[1].b, edges[2].b};
  const int64_t c[3] = {edges[0].c, edges[1].c, edges[2].c};
  return smallTileTests(a, b, c, bounds.x0, bounds.y0, bounds.x1, bounds.y1, format.fractionBits,
                        reach);
}

}  // namespace rast
