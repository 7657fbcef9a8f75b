// Coverage of an 8x8 tile of pixel-centre samples as one 64-bit mask: the scalar reference kernel
// and the whole-tile classification used to skip per-sample work.
#pragma once

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

// Samples of the tile inside `rect` (the triangle's bounds clipped to viewport and scissor).
CoverageMask rectMask(const PixelRect& rect, int tileX, int tileY);

// Per sample, the three edge functions evaluated directly in int64_t: the reference every faster
// kernel is compared with bit for bit. Samples outside `bounds` are not covered.
CoverageMask coverageScalar(const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                            int tileX, int tileY, FixedPointFormat format);

enum class TileCoverage { Outside, Inside, Partial };

// Whole-tile test from the edge values at the four corner samples of the tile: E is linear, so its
// extremes over the 64 samples lie at those corners. Outside: some edge is negative at all four.
// Inside: every edge is >= 0 at all four and the tile lies inside `bounds`.
TileCoverage classifyTile(const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                          int tileX, int tileY, FixedPointFormat format);

}  // namespace rast
