#include "pipeline/setup_batch.h"

#include <algorithm>
#include <cfloat>

namespace rast::detail {
namespace {

// The AVX-512 build: F for the doubles, DQ for the 64-bit products and conversions, VL and BW
// for the narrower vectors of the 32-bit values.
#define RAST_SETUP_AVX512 "avx512f,avx512dq,avx512vl,avx512bw"

// Each loop runs over the lanes with setupTriangle's operations on one lane's values, in its
// order; the compiler vectorises them (no FMA: -ffp-contract=off).

[[gnu::always_inline]] inline void windowAndSnapBody(const SetupCornersConstants& k, int lanes,
                                                     SetupCorners& c) {
  for (int l = 0; l < lanes; ++l) c.finite[l] = 1;
  for (int i = 0; i < 3; ++i) {
    double wx[kSetupLanes], wy[kSetupLanes];
    // ScreenMapping::toWindow, and std::isfinite of its four values: |v| <= DBL_MAX is false
    // exactly for infinities and NaN.
    for (int l = 0; l < lanes; ++l) {
      const double invW = 1.0 / c.p[i][3][l];
      wx[l] = c.p[i][0][l] * invW * k.scale[0] + k.offset[0];
      wy[l] = c.p[i][1][l] * invW * k.scale[1] + k.offset[1];
      c.z[i][l] = c.p[i][2][l] * invW * k.scale[2] + k.offset[2];
      c.invW[i][l] = invW;
      // (&, not &&: no branch per value, so the loop vectorises.)
      c.finite[l] &= int64_t(std::abs(wx[l]) <= DBL_MAX) & int64_t(std::abs(wy[l]) <= DBL_MAX) &
                     int64_t(std::abs(c.z[i][l]) <= DBL_MAX) & int64_t(std::abs(invW) <= DBL_MAX);
    }
    // snapToSubpixels. A lane that is not finite snaps zeros (its triangle is dropped) rather
    // than convert a NaN to an integer.
    for (int l = 0; l < lanes; ++l) {
      const double limit = k.guardBand;
      const double sx = (std::abs(wx[l]) <= DBL_MAX ? wx[l] : 0.0) * k.subpixelsPerPixel;
      const double cx = sx < -limit ? -limit : (sx > limit ? limit : sx);
      c.x[i][l] = int32_t((cx + 0x1.8p52) - 0x1.8p52);
      const double sy = (std::abs(wy[l]) <= DBL_MAX ? wy[l] : 0.0) * k.subpixelsPerPixel;
      const double cy = sy < -limit ? -limit : (sy > limit ? limit : sy);
      c.y[i][l] = int32_t((cy + 0x1.8p52) - 0x1.8p52);
    }
  }
}

// setupCoverage lane by lane. Its int64 arithmetic on the bounds fits int32 here: corners lie
// within 2^26 subpixels of the origin (fixed_point.h) and the sample reach is below a pixel
// (2^8 subpixels at most), so every sum below is under 2^27 in magnitude and the shifts give
// setupCoverage's pixels. Corner differences (the edges' a and b) are below 2^27 too; their
// products, up to 2^54, are taken in int64 as in EdgeFunction::through and setupCoverage.
[[gnu::always_inline]] inline void coverageLanesBody(const SetupCoverageConstants& k,
                                                     const SetupCorners& c, int lanes,
                                                     SetupCoverageLanes& out) {
  const int32_t s = int32_t{1} << k.fractionBits;
  // ownsTies: left edges (a > 0), and horizontal ones whose interior lies below (TopLeft: b > 0)
  // or above (BottomLeft: b < 0).
  const int32_t horizontalSign = k.rule == FillRule::TopLeft ? 1 : -1;
  for (int l = 0; l < lanes; ++l) {
    const int32_t x0 = c.x[0][l], y0 = c.y[0][l];
    const int64_t area = int64_t(c.x[1][l] - x0) * int64_t(c.y[2][l] - y0) -
                         int64_t(c.x[2][l] - x0) * int64_t(c.y[1][l] - y0);
    const bool clockwise = area > 0;
    // Counter-clockwise corners are taken as (v0, v2, v1), so that the interior is positive.
    const int32_t x1 = clockwise ? c.x[1][l] : c.x[2][l], y1 = clockwise ? c.y[1][l] : c.y[2][l];
    const int32_t x2 = clockwise ? c.x[2][l] : c.x[1][l], y2 = clockwise ? c.y[2][l] : c.y[1][l];
    const int32_t fromX[3] = {x0, x1, x2}, fromY[3] = {y0, y1, y2};
    const int32_t toX[3] = {x1, x2, x0}, toY[3] = {y1, y2, y0};
    int32_t bias[3];
    for (int e = 0; e < 3; ++e) {
      const int32_t a = fromY[e] - toY[e], b = toX[e] - fromX[e];
      const bool ownsTies = (a > 0) | ((a == 0) & (b * horizontalSign > 0));
      out.a[e][l] = a;
      out.b[e][l] = b;
      bias[e] = ownsTies ? 0 : 1;
      out.c[e][l] = -(int64_t(a) * fromX[e] + int64_t(b) * fromY[e]) - bias[e];
    }
    out.clockwise[l] = clockwise;

    const int32_t minX = std::min(std::min(x0, x1), x2) - k.sampleReach;
    const int32_t maxX = std::max(std::max(x0, x1), x2) + k.sampleReach;
    const int32_t minY = std::min(std::min(y0, y1), y2) - k.sampleReach;
    const int32_t maxY = std::max(std::max(y0, y1), y2) + k.sampleReach;
    const int32_t bx0 = std::max((minX - s / 2 + s - 1) >> k.fractionBits, k.clip.x0);
    const int32_t by0 = std::max((minY - s / 2 + s - 1) >> k.fractionBits, k.clip.y0);
    const int32_t bx1 = std::min(((maxX - s / 2) >> k.fractionBits) + 1, k.clip.x1);
    const int32_t by1 = std::min(((maxY - s / 2) >> k.fractionBits) + 1, k.clip.y1);
    out.x0[l] = bx0;
    out.y0[l] = by0;
    out.x1[l] = bx1;
    out.y1[l] = by1;
    const bool empty = (bx0 >= bx1) | (by0 >= by1);
    // setupCoverage's test of a triangle narrower and shorter than two pixels, at the (at most
    // 2x2) centres in its bounds. Its corners lie within 2s of each other per axis (s: subpixels
    // per pixel, at most 2^8), so |a|, |b| < 2s, and a centre tested lies within 3s of every
    // corner per axis: each value a*dx + b*dy - bias is below 12 s^2 + 1 <= 2^20 in magnitude.
    // Taken modulo 2^32 (uint32, which wraps where int32 would overflow in the lanes whose result
    // is not used), it is exact read back as int32.
    const uint32_t ucx = uint32_t(bx0) * uint32_t(s) + uint32_t(s / 2);
    const uint32_t ucy = uint32_t(by0) * uint32_t(s) + uint32_t(s / 2);
    // A centre is covered when no edge value there is negative: when the OR of the three has a
    // clear sign bit. The sign bit is set for a centre outside the bounds.
    const uint32_t outsideX = bx0 + 1 < bx1 ? 0 : 0x80000000u;
    const uint32_t outsideY = by0 + 1 < by1 ? 0 : 0x80000000u;
    uint32_t s00 = 0, s10 = outsideX, s01 = outsideY, s11 = outsideX | outsideY;
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = uint32_t(out.a[e][l]), b = uint32_t(out.b[e][l]);
      const uint32_t v = a * (ucx - uint32_t(fromX[e])) + b * (ucy - uint32_t(fromY[e])) -
                         uint32_t(bias[e]);
      const uint32_t vx = v + (a << k.fractionBits), vy = v + (b << k.fractionBits);
      s00 |= v;
      s10 |= vx;
      s01 |= vy;
      s11 |= vx + (b << k.fractionBits);
    }
    const bool coversCentre = int32_t(s00 & s10 & s01 & s11) >= 0;
    const bool small = (maxX - minX < 2 * s) & (maxY - minY < 2 * s) & (k.sampleReach == 0);
    out.outcome[l] = int32_t(area == 0                       ? SetupOutcome::ZeroArea
                             : empty | (small & !coversCentre) ? SetupOutcome::NoSamples
                                                               : SetupOutcome::Accepted);
  }
}

[[gnu::always_inline]] inline void planeGeometryBody(const SetupCorners& c, double pixelsPerSubpixel,
                                                     int lanes, SetupPlaneInputs& out) {
  for (int i = 0; i < 3; ++i)
    for (int l = 0; l < lanes; ++l) {
      out.x[i][l] = double(c.x[i][l]) * pixelsPerSubpixel;  // subpixelsToPixels
      out.y[i][l] = double(c.y[i][l]) * pixelsPerSubpixel;
    }
  // 1 / twice the signed area, as setupTriangle (setup.h) computes it.
  for (int l = 0; l < lanes; ++l) {
    const double signedArea = (out.x[1][l] - out.x[0][l]) * (out.y[2][l] - out.y[0][l]) -
                              (out.x[2][l] - out.x[0][l]) * (out.y[1][l] - out.y[0][l]);
    out.inverseDoubleArea[l] = 1.0 / signedArea;
  }
}

// PlaneEquation::through, lane by lane.
[[gnu::always_inline]] inline void planesThroughBody(const SetupPlaneInputs& in,
                                                     const SetupCoverageLanes& bounds,
                                                     const double (&value)[3][kSetupLanes],
                                                     int lanes, SetupPlanes& out) {
  for (int l = 0; l < lanes; ++l) {
    const double x0 = in.x[0][l], x1 = in.x[1][l], x2 = in.x[2][l];
    const double y0 = in.y[0][l], y1 = in.y[1][l], y2 = in.y[2][l];
    const double d1 = value[1][l] - value[0][l], d2 = value[2][l] - value[0][l];
    const double ddx = (d1 * (y2 - y0) - d2 * (y1 - y0)) * in.inverseDoubleArea[l];
    const double ddy = (d2 * (x1 - x0) - d1 * (x2 - x0)) * in.inverseDoubleArea[l];
    const double at0 = value[0][l] + ddx * (double(bounds.x0[l]) + 0.5 - x0) +
                       ddy * (double(bounds.y0[l]) + 0.5 - y0);
    out.at0[l] = float(at0);
    out.ddx[l] = float(ddx);
    out.ddy[l] = float(ddy);
  }
}

void windowAndSnapBaseline(const SetupCornersConstants& k, int lanes, SetupCorners& c) {
  windowAndSnapBody(k, lanes, c);
}
[[gnu::target("avx2")]] void windowAndSnapAvx2(const SetupCornersConstants& k, int lanes,
                                              SetupCorners& c) {
  windowAndSnapBody(k, lanes, c);
}
[[gnu::target(RAST_SETUP_AVX512)]] void windowAndSnapAvx512(const SetupCornersConstants& k, int lanes,
                                                 SetupCorners& c) {
  windowAndSnapBody(k, lanes, c);
}
void planeGeometryBaseline(const SetupCorners& c, double pps, int lanes, SetupPlaneInputs& out) {
  planeGeometryBody(c, pps, lanes, out);
}
[[gnu::target("avx2")]] void planeGeometryAvx2(const SetupCorners& c, double pps, int lanes,
                                              SetupPlaneInputs& out) {
  planeGeometryBody(c, pps, lanes, out);
}
[[gnu::target(RAST_SETUP_AVX512)]] void planeGeometryAvx512(const SetupCorners& c, double pps, int lanes,
                                                 SetupPlaneInputs& out) {
  planeGeometryBody(c, pps, lanes, out);
}
void planesThroughBaseline(const SetupPlaneInputs& in, const SetupCoverageLanes& bounds,
                           const double (&value)[3][kSetupLanes], int lanes, SetupPlanes& out) {
  planesThroughBody(in, bounds, value, lanes, out);
}
[[gnu::target("avx2")]] void planesThroughAvx2(const SetupPlaneInputs& in,
                                              const SetupCoverageLanes& bounds,
                                              const double (&value)[3][kSetupLanes], int lanes,
                                              SetupPlanes& out) {
  planesThroughBody(in, bounds, value, lanes, out);
}
[[gnu::target(RAST_SETUP_AVX512)]] void planesThroughAvx512(const SetupPlaneInputs& in,
                                                 const SetupCoverageLanes& bounds,
                                                 const double (&value)[3][kSetupLanes], int lanes,
                                                 SetupPlanes& out) {
  planesThroughBody(in, bounds, value, lanes, out);
}
void coverageLanesBaseline(const SetupCoverageConstants& k, const SetupCorners& c, int lanes,
                           SetupCoverageLanes& out) {
  coverageLanesBody(k, c, lanes, out);
}
[[gnu::target("avx2")]] void coverageLanesAvx2(const SetupCoverageConstants& k,
                                              const SetupCorners& c, int lanes,
                                              SetupCoverageLanes& out) {
  coverageLanesBody(k, c, lanes, out);
}
[[gnu::target(RAST_SETUP_AVX512)]] void coverageLanesAvx512(const SetupCoverageConstants& k,
                                                 const SetupCorners& c, int lanes,
                                                 SetupCoverageLanes& out) {
  coverageLanesBody(k, c, lanes, out);
}

}  // namespace

SetupIsa bestSetupIsa() {
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw"))
    return SetupIsa::Avx512;
  return __builtin_cpu_supports("avx2") ? SetupIsa::Avx2 : SetupIsa::Baseline;
}

const char* setupIsaName(SetupIsa isa) {
  switch (isa) {
    case SetupIsa::Baseline: return "baseline";
    case SetupIsa::Avx2: return "AVX2";
    case SetupIsa::Avx512: return "AVX-512";
  }
  return "?";
}

void windowAndSnap(const SetupCornersConstants& k, int lanes, SetupCorners& c, SetupIsa isa) {
  switch (isa) {
    case SetupIsa::Avx512: return windowAndSnapAvx512(k, lanes, c);
    case SetupIsa::Avx2: return windowAndSnapAvx2(k, lanes, c);
    case SetupIsa::Baseline: return windowAndSnapBaseline(k, lanes, c);
  }
}

void planeGeometry(const SetupCorners& c, double pixelsPerSubpixel, int lanes,
                   SetupPlaneInputs& out, SetupIsa isa) {
  switch (isa) {
    case SetupIsa::Avx512: return planeGeometryAvx512(c, pixelsPerSubpixel, lanes, out);
    case SetupIsa::Avx2: return planeGeometryAvx2(c, pixelsPerSubpixel, lanes, out);
    case SetupIsa::Baseline: return planeGeometryBaseline(c, pixelsPerSubpixel, lanes, out);
  }
}

void planesThrough(const SetupPlaneInputs& in, const SetupCoverageLanes& bounds,
                   const double (&value)[3][kSetupLanes], int lanes, SetupPlanes& out,
                   SetupIsa isa) {
  switch (isa) {
    case SetupIsa::Avx512: return planesThroughAvx512(in, bounds, value, lanes, out);
    case SetupIsa::Avx2: return planesThroughAvx2(in, bounds, value, lanes, out);
    case SetupIsa::Baseline: return planesThroughBaseline(in, bounds, value, lanes, out);
  }
}

void coverageLanes(const SetupCoverageConstants& k, const SetupCorners& c, int lanes,
                   SetupCoverageLanes& out, SetupIsa isa) {
  switch (isa) {
    case SetupIsa::Avx512: return coverageLanesAvx512(k, c, lanes, out);
    case SetupIsa::Avx2: return coverageLanesAvx2(k, c, lanes, out);
    case SetupIsa::Baseline: return coverageLanesBaseline(k, c, lanes, out);
  }
}

}  // namespace rast::detail
