#include "rasterizer/coverage.h"

#include <algorithm>

namespace rast {

CoverageMask coverageScalar(const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                            int tileX, int tileY, FixedPointFormat format, int32_t offsetX,
                            int32_t offsetY) {
  CoverageMask mask = 0;
  for (int ly = 0; ly < kTileSize; ++ly) {
    const int py = tileY * kTileSize + ly;
    const int64_t sy = pixelCentreSubpixels(py, format) + offsetY;
    for (int lx = 0; lx < kTileSize; ++lx) {
      const int px = tileX * kTileSize + lx;
      const int64_t sx = pixelCentreSubpixels(px, format) + offsetX;
      const bool inside = edges[0].at(sx, sy) >= 0 && edges[1].at(sx, sy) >= 0 &&
                          edges[2].at(sx, sy) >= 0;
      if (inside) mask |= CoverageMask{1} << coverageBit(lx, ly);
    }
  }
  return mask & rectMask(bounds, tileX, tileY);
}

TileCoverage classifyTile(const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                          int tileX, int tileY, FixedPointFormat format, int32_t reach) {
  const int64_t sx0 = pixelCentreSubpixels(tileX * kTileSize, format) - reach;
  const int64_t sy0 = pixelCentreSubpixels(tileY * kTileSize, format) - reach;
  const int64_t span = (int64_t(kTileSize - 1) << format.fractionBits) + 2 * int64_t(reach);
  bool allInside = true;
  for (const EdgeFunction& e : edges) {
    const int64_t e00 = e.at(sx0, sy0);
    const int64_t dx = int64_t{e.a} * span, dy = int64_t{e.b} * span;
    const int64_t lo = e00 + std::min<int64_t>(dx, 0) + std::min<int64_t>(dy, 0);
    const int64_t hi = e00 + std::max<int64_t>(dx, 0) + std::max<int64_t>(dy, 0);
    if (hi < 0) return TileCoverage::Outside;
    if (lo < 0) allInside = false;
  }
  const PixelRect tile{tileX * kTileSize, tileY * kTileSize, (tileX + 1) * kTileSize,
                       (tileY + 1) * kTileSize};
  if (allInside && bounds.intersect(tile) == tile) return TileCoverage::Inside;
  return TileCoverage::Partial;
}

}  // namespace rast
