#include "rasterizer/triangle_setup.h"

#include <algorithm>

namespace rast {
namespace {

// First pixel p whose centre p*S + S/2 is >= lo, and last whose centre is <= hi, S = 2^F: the
// floor of a quotient by a power of two is an arithmetic right shift (C++20 defines it for
// negative values), where a division would cost four 64-bit divides per triangle.
int firstPixelAtOrAfter(int64_t lo, FixedPointFormat f) {
  const int64_t s = f.subpixelsPerPixel();
  return int((lo - s / 2 + s - 1) >> f.fractionBits);
}
int lastPixelAtOrBefore(int64_t hi, FixedPointFormat f) {
  const int64_t s = f.subpixelsPerPixel();
  return int((hi - s / 2) >> f.fractionBits);
}

}  // namespace

SetupOutcome setupCoverage(const std::array<SnappedPoint, 3>& v, const PixelRect& clip,
                           FixedPointFormat format, CoverageSetup& out, FillRule rule,
                           int32_t sampleReach) {
  // Twice the signed area with y down: positive for a clockwise triangle on screen.
  const int64_t area = (int64_t(v[1].x) - v[0].x) * (int64_t(v[2].y) - v[0].y) -
                       (int64_t(v[2].x) - v[0].x) * (int64_t(v[1].y) - v[0].y);
  if (area == 0) return SetupOutcome::ZeroArea;

  out.clockwiseOnScreen = area > 0;
  out.doubleArea = area > 0 ? area : -area;
  const SnappedPoint p0 = v[0];
  const SnappedPoint p1 = area > 0 ? v[1] : v[2];
  const SnappedPoint p2 = area > 0 ? v[2] : v[1];
  out.edges = {EdgeFunction::through(p0, p1, rule), EdgeFunction::through(p1, p2, rule),
               EdgeFunction::through(p2, p0, rule)};

  const int64_t minX = std::min({v[0].x, v[1].x, v[2].x}) - sampleReach;
  const int64_t maxX = std::max({v[0].x, v[1].x, v[2].x}) + sampleReach;
  const int64_t minY = std::min({v[0].y, v[1].y, v[2].y}) - sampleReach;
  const int64_t maxY = std::max({v[0].y, v[1].y, v[2].y}) + sampleReach;
  const PixelRect box{firstPixelAtOrAfter(minX, format), firstPixelAtOrAfter(minY, format),
                      lastPixelAtOrBefore(maxX, format) + 1, lastPixelAtOrBefore(maxY, format) + 1};
  out.bounds = box.intersect(clip);
  if (out.bounds.empty()) return SetupOutcome::NoSamples;
  // A triangle narrower and shorter than two pixels has at most 2x2 centres in its bounds; they
  // are tested here, and one that covers none is dropped with those whose bounds hold none. W2
  // tiny-1: a sixth of its triangles, which would otherwise each cost a record, a bin entry and
  // the back end's visit. Larger ones are left to the back end, which tests them anyway.
  const int64_t s = format.subpixelsPerPixel();
  if (sampleReach == 0 && maxX - minX < 2 * s && maxY - minY < 2 * s) {
    for (int py = out.bounds.y0; py < out.bounds.y1; ++py)
      for (int px = out.bounds.x0; px < out.bounds.x1; ++px) {
        const int64_t x = pixelCentreSubpixels(px, format), y = pixelCentreSubpixels(py, format);
        if (out.edges[0].at(x, y) >= 0 && out.edges[1].at(x, y) >= 0 &&
            out.edges[2].at(x, y) >= 0)
          return SetupOutcome::Accepted;
      }
    return SetupOutcome::NoSamples;
  }
  return SetupOutcome::Accepted;
}

}  // namespace rast
