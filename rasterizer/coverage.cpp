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
  return classifyTiles(edges, bounds, tileX, tileX, tileY, tileY, format, reach);
}

TileCoverage classifyTiles(const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                           int tileX0, int tileX1, int tileY0, int tileY1, FixedPointFormat format,
                           int32_t reach) {
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
