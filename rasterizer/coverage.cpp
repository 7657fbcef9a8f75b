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

}  // namespace rast
