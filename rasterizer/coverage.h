// Coverage of an 8x8 tile of pixel-centre samples as one 64-bit mask: the scalar reference kernel
// and the whole-tile classification used to skip per-sample work.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "rasterizer/edge_function.h"
#include "rasterizer/fixed_point.h"
#include "rasterizer/pixel_rect.h"

namespace rast {

inline constexpr int kTileSize = 8;
inline constexpr int kTileShift = 3;

// Bit i is the pixel (i % 8, i / 8) of the tile, counted from the tile's top-left pixel.
using CoverageMask = uint64_t;
inline constexpr CoverageMask kFullMask = ~CoverageMask{0};

constexpr int coverageBit(int localX, int localY) { return localY * kTileSize + localX; }

// Set bits of a mask. Written out because the baseline x86-64 target has no popcnt instruction
// and std::popcount becomes a library call there; this is a dozen inline operations (forced
// inline: the back end's statistics count with it per triangle and tile, and GCC made it a call).
[[gnu::always_inline]] constexpr int popcount64(uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ull);
  x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
  return int((x * 0x0101010101010101ull) >> 56);
}

// Samples of the tile inside `rect` (the triangle's bounds clipped to viewport and scissor).
// Inline: the back end asks for it once per tile and coverTile once per (triangle, tile), where
// a call of its own took 2 % of W1's frame.
inline CoverageMask rectMask(const PixelRect& rect, int tileX, int tileY) {
  const int ox = tileX * kTileSize, oy = tileY * kTileSize;
  const int x0 = std::clamp(rect.x0 - ox, 0, kTileSize), x1 = std::clamp(rect.x1 - ox, 0, kTileSize);
  const int y0 = std::clamp(rect.y0 - oy, 0, kTileSize), y1 = std::clamp(rect.y1 - oy, 0, kTileSize);
  if (x0 >= x1 || y0 >= y1) return 0;
  // The row's bits copied into all eight bytes, then the rows outside [y0, y1) cleared.
  const uint64_t row = ((uint64_t{1} << (x1 - x0)) - 1) << x0;
  const uint64_t columns = row * 0x0101010101010101ull;
  const uint64_t rows = (y1 == kTileSize ? ~uint64_t{0} : (uint64_t{1} << (8 * y1)) - 1) &
                        ~((uint64_t{1} << (8 * y0)) - 1);
  return columns & rows;
}

// Per sample, the three edge functions evaluated directly in int64_t: the reference every faster
// kernel is compared with bit for bit. Samples of pixels outside `bounds` are not covered. The
// sample of each pixel lies (offsetX, offsetY) subpixels from its centre (MSAA; 0 otherwise).
CoverageMask coverageScalar(const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                            int tileX, int tileY, FixedPointFormat format, int32_t offsetX = 0,
                            int32_t offsetY = 0);

enum class TileCoverage { Outside, Inside, Partial };

// Whole-tile test from the edge values at the four corner samples of the tile: E is linear, so its
// extremes over the 64 samples lie at those corners. Outside: some edge is negative at all four.
// Inside: every edge is >= 0 at all four and the tile lies inside `bounds`. With `reach` > 0 the
// corners move out by `reach` subpixels, so the answer holds for every sample within `reach` of
// a pixel centre (all samples of an MSAA pattern).
// Forced inline (defined below): the back end takes it for empty small rectangles, once per
// entry, and GCC left it a call in the larger tile loops.
[[gnu::always_inline]] inline TileCoverage classifyTile(const std::array<EdgeFunction, 3>& edges,
                                                       const PixelRect& bounds, int tileX,
                                                       int tileY, FixedPointFormat format,
                                                       int32_t reach = 0);

// The same test for the rectangle of tiles [tileX0, tileX1] x [tileY0, tileY1] (inclusive) as a
// whole (binning's coarse tiles): Outside says every tile of it is Outside, Inside that every
// tile is Inside. (Forced inline, as classifyTile.)
[[gnu::always_inline]] inline TileCoverage classifyTiles(const std::array<EdgeFunction, 3>& edges,
                                                        const PixelRect& bounds, int tileX0,
                                                        int tileX1, int tileY0, int tileY1,
                                                        FixedPointFormat format,
                                                        int32_t reach = 0);

// An edge's least and greatest values over the samples of a rectangle of `colsPixels` x
// `rowsPixels` pixel centres widened by `reach`, minus its value at the rectangle's top-left
// (widened) corner: E is linear, so they lie at corners, a sum of the positive (or negative)
// parts of a*spanX and b*spanY.
struct EdgeExtent {
  int64_t lowest, highest;
};
[[gnu::always_inline]] inline EdgeExtent edgeExtent(const EdgeFunction& e, int colsPixels,
                                                    int rowsPixels, FixedPointFormat format,
                                                    int32_t reach) {
  const int64_t spanX = (int64_t(colsPixels - 1) << format.fractionBits) + 2 * int64_t(reach);
  const int64_t spanY = (int64_t(rowsPixels - 1) << format.fractionBits) + 2 * int64_t(reach);
  const int64_t dx = int64_t{e.a} * spanX, dy = int64_t{e.b} * spanY;
  return {std::min<int64_t>(dx, 0) + std::min<int64_t>(dy, 0),
          std::max<int64_t>(dx, 0) + std::max<int64_t>(dy, 0)};
}

[[gnu::always_inline]] inline TileCoverage classifyTile(const std::array<EdgeFunction, 3>& edges,
                                                       const PixelRect& bounds, int tileX,
                                                       int tileY, FixedPointFormat format,
                                                       int32_t reach) {
  return classifyTiles(edges, bounds, tileX, tileX, tileY, tileY, format, reach);
}

[[gnu::always_inline]] inline TileCoverage classifyTiles(const std::array<EdgeFunction, 3>& edges,
                                                        const PixelRect& bounds, int tileX0,
                                                        int tileX1, int tileY0, int tileY1,
                                                        FixedPointFormat format, int32_t reach) {
  const int64_t sx0 = pixelCentreSubpixels(tileX0 * kTileSize, format) - reach;
  const int64_t sy0 = pixelCentreSubpixels(tileY0 * kTileSize, format) - reach;
  const int cols = (tileX1 - tileX0 + 1) * kTileSize, rows = (tileY1 - tileY0 + 1) * kTileSize;
  bool allInside = true;
  for (const EdgeFunction& e : edges) {
    const int64_t e00 = e.at(sx0, sy0);
    const EdgeExtent extent = edgeExtent(e, cols, rows, format, reach);
    if (e00 + extent.highest < 0) return TileCoverage::Outside;
    if (e00 + extent.lowest < 0) allInside = false;
  }
  const PixelRect tiles{tileX0 * kTileSize, tileY0 * kTileSize, (tileX1 + 1) * kTileSize,
                        (tileY1 + 1) * kTileSize};
  if (allInside && bounds.intersect(tiles) == tiles) return TileCoverage::Inside;
  return TileCoverage::Partial;
}

}  // namespace rast
