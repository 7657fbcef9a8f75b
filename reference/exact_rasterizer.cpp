#include "reference/exact_rasterizer.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace rast::reference {
namespace {

using Int = __int128;

// Grid coordinates and samples stay below 2^61 in magnitude, so differences stay below 2^62,
// products below 2^124 and the orientation below 2^125: no __int128 can overflow.
constexpr double kGridLimit = 0x1p60;

Int orient(Int ax, Int ay, Int bx, Int by, Int cx, Int cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

int sign(Int v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

// Fraction bits v needs to be an integer multiple of 2^-bits.
int fractionBitsOf(double v) {
  if (v == 0) return 0;
  int e = 0;
  const double m = std::frexp(std::abs(v), &e);  // v = m 2^e, m in [1/2, 1)
  const auto mantissa = uint64_t(std::ldexp(m, 53));  // exact: 53 significant bits
  return std::max(0, 53 - e - std::countr_zero(mantissa));
}

Int sampleOnGrid(int p, int fractionBits) { return (Int(2) * p + 1) << (fractionBits - 1); }

// Edge p -> q of a triangle whose third vertex is r: is it a top edge (horizontal, the triangle
// below it, y pointing down) or a left edge (not horizontal, the triangle to its right)?
bool isTopOrLeft(Int px, Int py, Int qx, Int qy, Int rx, Int ry) {
  if (py == qy) return ry > py;
  // r lies right of the line through p and q at r's height:
  // r.x - p.x > (q.x - p.x)(r.y - p.y)/(q.y - p.y), multiplied out with the sign of q.y - p.y.
  const Int cross = (rx - px) * (qy - py) - (qx - px) * (ry - py);
  return sign(cross) * sign(qy - py) > 0;
}

}  // namespace

WindowTriangle roundedToFloat(const WindowTriangle& t) {
  WindowTriangle out;
  for (int i = 0; i < 3; ++i) {
    const volatile float x = float(t[i].x), y = float(t[i].y);
    out[i] = {x, y};
  }
  return out;
}

int64_t snapExactly(double v, FixedPointFormat format) {
  const double limit = format.guardBandSubpixels();
  if (v > limit) return int64_t(limit);  // beyond the band in pixels, so also in subpixels
  if (v < -limit) return -int64_t(limit);
  const double scaled = std::ldexp(v, format.fractionBits);  // exact: a power of two
  const double below = std::floor(scaled);
  const double fraction = scaled - below;  // exact: both lie within one binade step of scaled
  double rounded = below;
  if (fraction > 0.5 || (fraction == 0.5 && std::fmod(below, 2.0) != 0)) rounded = below + 1;
  return int64_t(std::clamp(rounded, -limit, limit));
}

bool toGrid(const WindowTriangle& t, const ExactGeometry& geometry, GridTriangle& out) {
  for (const WindowPoint& p : t)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  if (geometry.snap) {
    out.fractionBits = geometry.format.fractionBits;
    for (int i = 0; i < 3; ++i) {
      out.x[i] = snapExactly(t[i].x, geometry.format);
      out.y[i] = snapExactly(t[i].y, geometry.format);
    }
    return true;
  }
  int bits = 1;  // samples need one
  for (const WindowPoint& p : t) bits = std::max({bits, fractionBitsOf(p.x), fractionBitsOf(p.y)});
  if (bits > 64) return false;
  out.fractionBits = bits;
  for (int i = 0; i < 3; ++i) {
    const double x = std::ldexp(t[i].x, bits), y = std::ldexp(t[i].y, bits);  // integers
    if (std::abs(x) > kGridLimit || std::abs(y) > kGridLimit) return false;
    out.x[i] = Int(int64_t(x));
    out.y[i] = Int(int64_t(y));
  }
  return true;
}

bool coversPixelCentre(const GridTriangle& t, int px, int py, SampleRule rule) {
  const Int sx = sampleOnGrid(px, t.fractionBits), sy = sampleOnGrid(py, t.fractionBits);
  // Outside the bounding box nothing is covered (and the bound on grid values holds inside it).
  if (sx < std::min({t.x[0], t.x[1], t.x[2]}) || sx > std::max({t.x[0], t.x[1], t.x[2]}) ||
      sy < std::min({t.y[0], t.y[1], t.y[2]}) || sy > std::max({t.y[0], t.y[1], t.y[2]}))
    return false;
  const int winding = sign(orient(t.x[0], t.y[0], t.x[1], t.y[1], t.x[2], t.y[2]));
  if (winding == 0) return false;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    // The interior side of edge i -> j is the side of k, which has the triangle's winding.
    const int side = sign(orient(t.x[i], t.y[i], t.x[j], t.y[j], sx, sy)) * winding;
    if (side < 0) return false;
    if (side == 0 && rule == SampleRule::TopLeft &&
        !isTopOrLeft(t.x[i], t.y[i], t.x[j], t.y[j], t.x[k], t.y[k]))
      return false;
  }
  return true;
}

void forEachCoveredPixel(const GridTriangle& t, const PixelRect& clip, SampleRule rule,
                         const std::function<void(int, int)>& visit) {
  const int g = t.fractionBits;
  // Pixels whose centres can lie in the bounding box, one either side for good measure.
  auto pixelOf = [g](Int v) { return double(v >> g); };  // floor(v / 2^g)
  const double x0 = pixelOf(std::min({t.x[0], t.x[1], t.x[2]})) - 1;
  const double x1 = pixelOf(std::max({t.x[0], t.x[1], t.x[2]})) + 1;
  const double y0 = pixelOf(std::min({t.y[0], t.y[1], t.y[2]})) - 1;
  const double y1 = pixelOf(std::max({t.y[0], t.y[1], t.y[2]})) + 1;
  const int px0 = int(std::clamp<double>(x0, clip.x0, clip.x1));
  const int px1 = int(std::clamp<double>(x1, clip.x0 - 1, clip.x1 - 1));
  const int py0 = int(std::clamp<double>(y0, clip.y0, clip.y1));
  const int py1 = int(std::clamp<double>(y1, clip.y0 - 1, clip.y1 - 1));
  for (int y = py0; y <= py1; ++y)
    for (int x = px0; x <= px1; ++x)
      if (coversPixelCentre(t, x, y, rule)) visit(x, y);
}

CoverageCounts rasterizeCounts(std::span<const WindowTriangle> triangles, int width, int height,
                               const ExactGeometry& geometry) {
  CoverageCounts out;
  out.width = width;
  out.height = height;
  out.counts.assign(size_t(width) * size_t(height), 0);
  const PixelRect clip{0, 0, width, height};
  for (const WindowTriangle& t : triangles) {
    GridTriangle grid;
    if (!toGrid(t, geometry, grid)) {
      ++out.undecidable;
      continue;
    }
    forEachCoveredPixel(grid, clip, geometry.rule,
                        [&](int x, int y) { ++out.counts[size_t(y) * size_t(width) + size_t(x)]; });
  }
  return out;
}

std::array<double, 3> barycentricAtPixelCentre(const GridTriangle& t, int px, int py) {
  const Int sx = sampleOnGrid(px, t.fractionBits), sy = sampleOnGrid(py, t.fractionBits);
  const double area = double(orient(t.x[0], t.y[0], t.x[1], t.y[1], t.x[2], t.y[2]));
  return {double(orient(t.x[1], t.y[1], t.x[2], t.y[2], sx, sy)) / area,
          double(orient(t.x[2], t.y[2], t.x[0], t.y[0], sx, sy)) / area,
          double(orient(t.x[0], t.y[0], t.x[1], t.y[1], sx, sy)) / area};
}

double interpolateLinear(const std::array<double, 3>& l, const std::array<double, 3>& value) {
  return l[0] * value[0] + l[1] * value[1] + l[2] * value[2];
}

double interpolatePerspective(const std::array<double, 3>& l, const std::array<double, 3>& invW,
                              const std::array<double, 3>& value) {
  const double q = l[0] * value[0] * invW[0] + l[1] * value[1] * invW[1] + l[2] * value[2] * invW[2];
  const double r = l[0] * invW[0] + l[1] * invW[1] + l[2] * invW[2];
  return q / r;
}

}  // namespace rast::reference
