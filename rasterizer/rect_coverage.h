// Coverage of a small rectangle of a tile by direct evaluation: for a triangle whose bounds meet a
// tile in a few pixels (W2's small triangles, most of a mesh's), evaluating the edges at those
// pixels alone costs less than preparing the whole 8x8 tile for a coverage kernel.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include <emmintrin.h>

#include "rasterizer/coverage.h"
#include "rasterizer/edge_function.h"
#include "rasterizer/fixed_point.h"

namespace rast {

// Pixels [x0, x1) x [y0, y1) of a tile, counted from its top-left pixel.
struct TileRect {
  int x0, y0, x1, y1;
};

// The part of `bounds` inside tile (tileX, tileY), possibly empty. (Forced inline: the tile
// loop takes it per entry.)
[[gnu::always_inline]] inline TileRect tileRectOf(const PixelRect& bounds, int tileX, int tileY) {
  const int ox = tileX * kTileSize, oy = tileY * kTileSize;
  return {std::clamp(bounds.x0 - ox, 0, kTileSize), std::clamp(bounds.y0 - oy, 0, kTileSize),
          std::clamp(bounds.x1 - ox, 0, kTileSize), std::clamp(bounds.y1 - oy, 0, kTileSize)};
}

// The pixel-centre samples of `rect` (non-empty) inside the triangle: coverageScalar's mask
// restricted to `rect`, bit for bit. Each edge is evaluated exactly in int64 at the rectangle's
// first pixel (fixed_point.h: below 2^55) and stepped by a * 2^F per column and b * 2^F per row
// (below 2^35 each; at most seven column and eight row steps, so every sum stays far inside
// int64). Columns go four at a time, two 64-bit lanes per SSE2 register: SSE2 is the x86-64
// baseline, so both builds of the tile loop run these instructions. A sample is inside when no
// edge is negative, i.e. when the OR of the three values has a clear sign bit, which movmskpd
// reads without a 64-bit compare.
template <int Blocks>  // of four columns: 1 for rectangles up to four wide, 2 up to eight
[[gnu::always_inline]] inline CoverageMask coverRectColumns(const std::array<EdgeFunction, 3>& edges,
                                                            TileRect rect, int tileX, int tileY,
                                                            FixedPointFormat format) {
  const int64_t sx = pixelCentreSubpixels(tileX * kTileSize + rect.x0, format);
  const int64_t sy = pixelCentreSubpixels(tileY * kTileSize + rect.y0, format);
  const int f = format.fractionBits;
  __m128i pairs[3][2 * Blocks], down[3];  // pair j: columns x0 + 2j, x0 + 2j + 1
  for (int i = 0; i < 3; ++i) {
    const int64_t e = edges[i].at(sx, sy);
    const int64_t step = int64_t{edges[i].a} * (int64_t{1} << f);
    for (int j = 0; j < 2 * Blocks; ++j)
      pairs[i][j] = _mm_set_epi64x(e + (2 * j + 1) * step, e + 2 * j * step);
    down[i] = _mm_set1_epi64x(int64_t{edges[i].b} * (int64_t{1} << f));
  }
  const unsigned columns = (1u << (rect.x1 - rect.x0)) - 1;
  CoverageMask mask = 0;
  for (int row = rect.y0; row < rect.y1; ++row) {
    unsigned outside = 0;
    for (int j = 0; j < 2 * Blocks; ++j) {
      const __m128i any = _mm_or_si128(_mm_or_si128(pairs[0][j], pairs[1][j]), pairs[2][j]);
      outside |= unsigned(_mm_movemask_pd(_mm_castsi128_pd(any))) << (2 * j);
    }
    mask |= CoverageMask(~outside & columns) << (row * kTileSize + rect.x0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2 * Blocks; ++j) pairs[i][j] = _mm_add_epi64(pairs[i][j], down[i]);
  }
  return mask;
}

[[gnu::always_inline]] inline CoverageMask coverRect(const std::array<EdgeFunction, 3>& edges,
                                                     TileRect rect, int tileX, int tileY,
                                                     FixedPointFormat format) {
  return rect.x1 - rect.x0 <= 4 ? coverRectColumns<1>(edges, rect, tileX, tileY, format)
                                : coverRectColumns<2>(edges, rect, tileX, tileY, format);
}

}  // namespace rast
