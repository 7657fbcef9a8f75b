#include "rasterizer/float_coverage.h"

#include <algorithm>
#include <cmath>

namespace rast {
namespace {

FloatEdge edgeThrough(float fromX, float fromY, float toX, float toY) {
  FloatEdge e;
  e.a = fromY - toY;
  e.b = toX - fromX;
  e.c = -(e.a * fromX + e.b * fromY);
  return e;
}

float sampleCentre(int p) { return float(p) + 0.5f; }

// Smallest and largest value of edge e over the tile's samples, from its corners (exact: e is
// monotonic in each coordinate, see the header).
void edgeRangeOverTile(const FloatEdge& e, int tileX, int tileY, float& lo, float& hi) {
  const float x0 = sampleCentre(tileX * kTileSize), x1 = sampleCentre(tileX * kTileSize + kTileSize - 1);
  const float y0 = sampleCentre(tileY * kTileSize), y1 = sampleCentre(tileY * kTileSize + kTileSize - 1);
  const float v[4] = {e.at(x0, y0), e.at(x1, y0), e.at(x0, y1), e.at(x1, y1)};
  lo = std::min({v[0], v[1], v[2], v[3]});
  hi = std::max({v[0], v[1], v[2], v[3]});
}

}  // namespace

SetupOutcome setupFloatCoverage(const std::array<double, 3>& windowX,
                                const std::array<double, 3>& windowY, const PixelRect& clip,
                                CoverageSetup& out, FloatEdges& edges) {
  std::array<float, 3> x, y;
  for (int i = 0; i < 3; ++i) x[i] = float(windowX[i]), y[i] = float(windowY[i]);
  const float area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const double areaInDouble = (double(x[1]) - x[0]) * (double(y[2]) - y[0]) -
                              (double(x[2]) - x[0]) * (double(y[1]) - y[0]);
  if (area == 0 || areaInDouble == 0) return SetupOutcome::ZeroArea;

  out.clockwiseOnScreen = area > 0;
  edges.x = x;
  edges.y = y;
  for (int i = 0; i < 3; ++i) {
    const int j = area > 0 ? (i + 1) % 3 : (i + 2) % 3;
    edges.edges[i] = edgeThrough(x[i], y[i], x[j], y[j]);
  }

  // Pixel centres p + 1/2 inside [min, max]: exact in double for float bounds.
  const double minX = std::min({x[0], x[1], x[2]}), maxX = std::max({x[0], x[1], x[2]});
  const double minY = std::min({y[0], y[1], y[2]}), maxY = std::max({y[0], y[1], y[2]});
  const PixelRect box{int(std::ceil(minX - 0.5)), int(std::ceil(minY - 0.5)),
                      int(std::floor(maxX - 0.5)) + 1, int(std::floor(maxY - 0.5)) + 1};
  out.bounds = box.intersect(clip);
  return out.bounds.empty() ? SetupOutcome::NoSamples : SetupOutcome::Accepted;
}

TileCoverage classifyTileFloat(const FloatEdges& edges, const PixelRect& bounds, int tileX,
                               int tileY) {
  bool allInside = true;
  for (const FloatEdge& e : edges.edges) {
    float lo, hi;
    edgeRangeOverTile(e, tileX, tileY, lo, hi);
    if (hi < 0) return TileCoverage::Outside;
    if (!(lo >= 0)) allInside = false;
  }
  const PixelRect tile{tileX * kTileSize, tileY * kTileSize, (tileX + 1) * kTileSize,
                       (tileY + 1) * kTileSize};
  return allInside && bounds.intersect(tile) == tile ? TileCoverage::Inside : TileCoverage::Partial;
}

TileCoverageResult coverTileFloat(const FloatEdges& edges, const PixelRect& bounds, int tileX,
                                  int tileY) {
  const TileCoverage kind = classifyTileFloat(edges, bounds, tileX, tileY);
  if (kind == TileCoverage::Outside) return {0, kind};
  if (kind == TileCoverage::Inside) return {kFullMask, kind};
  CoverageMask mask = 0;
  for (int ly = 0; ly < kTileSize; ++ly) {
    const float sy = sampleCentre(tileY * kTileSize + ly);
    for (int lx = 0; lx < kTileSize; ++lx) {
      const float sx = sampleCentre(tileX * kTileSize + lx);
      const bool inside = edges.edges[0].at(sx, sy) >= 0 && edges.edges[1].at(sx, sy) >= 0 &&
                          edges.edges[2].at(sx, sy) >= 0;
      if (inside) mask |= CoverageMask{1} << coverageBit(lx, ly);
    }
  }
  return {mask & rectMask(bounds, tileX, tileY), TileCoverage::Partial};
}

}  // namespace rast
