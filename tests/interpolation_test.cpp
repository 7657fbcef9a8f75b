// Interpolation: varyings perspective-correct, depth (z/w) linear in screen space and in [0, 1],
// both compared with values computed here in double from the snapped vertex positions.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "pipeline/draw.h"
#include "pipeline/tile_loop.h"

namespace rast {
namespace {

template <int N>
struct PassThroughVS {
  using Vertex = ShadedVertex<N>;
  static constexpr int kVaryings = N;
  ShadedVertex<N> operator()(const Vertex& v) const { return v; }
};

// Records what the pipeline hands the pixel shader, at full float precision (a colour image
// would quantise it to 8 bits). Each pixel is written by at most one fragment in these tests.
template <int N>
struct CaptureShader {
  static constexpr int kVaryings = N;
  static constexpr bool kMayDiscard = false;
  std::vector<Varyings<N>>* varyings;
  std::vector<float>* depth;
  int width;

  PixelResult operator()(const Fragment<N>& f) const {
    (*varyings)[size_t(f.y) * width + f.x] = f.varyings;
    (*depth)[size_t(f.y) * width + f.x] = f.depth;
    return {};
  }
};

template <int N>
struct Captured {
  std::vector<Varyings<N>> varyings;
  std::vector<float> depth;
  std::vector<uint32_t> counts;
};

template <int N>
Captured<N> drawAndCapture(const PipelineState& state, int width, int height,
                           const std::vector<ShadedVertex<N>>& vertices,
                           const std::vector<uint32_t>& indices) {
  Captured<N> c;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Varyings<N> none;
  none.fill(nan);
  c.varyings.assign(size_t(width) * height, none);
  c.depth.assign(size_t(width) * height, nan);
  Framebuffer fb(width, height, true);
  PipelineStatistics stats;
  const PassThroughVS<N> vs;
  const CaptureShader<N> ps{&c.varyings, &c.depth, width};
  const Status s = draw(
      fb, state, DrawCall<PassThroughVS<N>, CaptureShader<N>>{vertices, indices, vs, ps}, stats);
  EXPECT_TRUE(s.isOk()) << s.message();
  c.counts = fb.countPlane();
  return c;
}

PipelineState captureState(int width, int height, FixedPointFormat format,
                           PositionSpace space = PositionSpace::Clip) {
  PipelineState s;
  s.viewport = {0, 0, width, height};
  s.format = format;
  s.positionSpace = space;
  s.depth.compare = CompareOp::Always;  // every fragment reaches the shader
  s.depth.write = false;
  return s;
}

// What setup sees of a vertex: window position (snapped, in pixels), depth and 1/w, computed as
// viewport.h documents it.
struct SnappedVertex {
  double x, y, z, invW;
};

SnappedVertex snapVertex(const glm::vec4& p, const PipelineState& state) {
  const double invW = 1.0 / double(p.w);
  double x = double(p.x), y = double(p.y), z = double(p.z);
  if (state.positionSpace == PositionSpace::Clip) {
    const Viewport& vp = state.viewport;
    x = x * invW * (0.5 * vp.width) + (vp.x + 0.5 * vp.width);
    y = y * invW * (-0.5 * vp.height) + (vp.y + 0.5 * vp.height);
    z = z * invW * 0.5 + 0.5;
  }
  const int f = state.format.fractionBits;
  return {std::ldexp(std::nearbyint(std::ldexp(x, f)), -f),
          std::ldexp(std::nearbyint(std::ldexp(y, f)), -f), z, invW};
}

// Screen-space barycentric coordinates of (px, py) in the snapped triangle.
std::array<double, 3> barycentric(const std::array<SnappedVertex, 3>& v, double px, double py) {
  const double area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
  const double l1 = ((px - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (py - v[0].y)) / area;
  const double l2 = ((v[1].x - v[0].x) * (py - v[0].y) - (px - v[0].x) * (v[1].y - v[0].y)) / area;
  return {1.0 - l1 - l2, l1, l2};
}

// The largest |plane value| + |d/dx| * width + |d/dy| * height over a rectangle: bounds the terms
// of a float evaluation at0 + ddx * dx + ddy * dy anchored anywhere in the rectangle.
double termBound(const std::array<SnappedVertex, 3>& v, const std::array<double, 3>& value,
                 double x0, double y0, double x1, double y1) {
  auto at = [&](double x, double y) {
    const auto l = barycentric(v, x, y);
    return l[0] * value[0] + l[1] * value[1] + l[2] * value[2];
  };
  const double gx = at(1, 0) - at(0, 0), gy = at(0, 1) - at(0, 0);
  const double corner = std::max(
      {std::abs(at(x0, y0)), std::abs(at(x1, y0)), std::abs(at(x0, y1)), std::abs(at(x1, y1))});
  return corner + std::abs(gx) * (x1 - x0) + std::abs(gy) * (y1 - y0);
}

constexpr double kFloatEps = 0x1p-24;  // unit roundoff of float

// ---------------------------------------------------------------------------------------------
// The reference text's example: a square seen obliquely, u running from its near edge (0) to its
// far edge (1). Its 3D centre lies on the optical axis, so it projects onto the centre of the
// middle pixel of an odd-sized viewport; there u must be 0.5, where interpolating u linearly in
// screen space would give a clearly different value.
TEST(InterpolationPerspective, ObliqueSquareCentreHasMidpointTexCoord) {
  constexpr int S = 65;
  const glm::dmat4 proj = glm::perspective(glm::radians(60.0), 1.0, 0.5, 20.0);
  const glm::dvec3 centre(0, 0, -4);
  const glm::dvec3 across(1.5, 0, 0);                                      // v: 0 .. 1
  const glm::dvec3 along = glm::dvec3(0, 0.5, -0.8660254037844386) * 2.5;  // u: 0 near, 1 far
  const std::array<glm::dvec3, 4> corners = {centre - across - along, centre + across - along,
                                             centre + across + along, centre - across + along};
  const std::array<std::array<float, 2>, 4> uv = {{{0, 0}, {0, 1}, {1, 1}, {1, 0}}};
  std::vector<ShadedVertex<2>> vertices;
  for (int k = 0; k < 4; ++k)
    vertices.push_back({glm::vec4(proj * glm::dvec4(corners[k], 1.0)), {uv[k][0], uv[k][1]}});
  // Corner 0 to corner 2 is the diagonal through the centre.
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};

  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    const PipelineState state = captureState(S, S, format);
    const Captured<2> c = drawAndCapture<2>(state, S, S, vertices, indices);
    const size_t mid = size_t(S / 2) * S + S / 2;
    ASSERT_EQ(c.counts[mid], 1u) << format.name();
    const float u = c.varyings[mid][0], v = c.varyings[mid][1];

    // Snapping moves each projected corner by at most 1/32 pixel (24.4); u changes by about 0.03
    // per pixel over this square, so the value at the centre moves by < 0.002. Float evaluation
    // adds ~1e-6.
    EXPECT_NEAR(u, 0.5, 0.003) << format.name();
    EXPECT_NEAR(v, 0.5, 0.003) << format.name();

    // Screen-space (affine) interpolation along the projected diagonal, for contrast: the centre
    // projects much nearer the far corner than the screen midpoint does.
    std::array<SnappedVertex, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = snapVertex(vertices[k].position, state);
    const double t = std::hypot(S / 2.0 - p[0].x, S / 2.0 - p[0].y) /
                     std::hypot(p[2].x - p[0].x, p[2].y - p[0].y);
    EXPECT_GT(std::abs(t - 0.5), 0.1) << "the example must tell the two apart";
    EXPECT_GT(std::abs(u - t), 0.1) << format.name() << ": u was interpolated in screen space";

    // Depth is z/w, linear in screen space: at the centre pixel it is the window depth of the 3D
    // centre itself. Tolerance: snapping moves the depth plane by < 1/32 pixel times its gradient
    // (< 3e-3 per pixel here): < 1e-4.
    const glm::dvec4 cc = proj * glm::dvec4(centre, 1.0);
    const double centreDepth = 0.5 * cc.z / cc.w + 0.5;
    EXPECT_NEAR(c.depth[mid], centreDepth, 1e-4) << format.name();
    // Interpolating depth perspective-correctly (like a varying) would give the average of the
    // diagonal's end depths there instead.
    EXPECT_GT(std::abs(0.5 * (p[0].z + p[2].z) - centreDepth), 1e-3);
  }
}

// ---------------------------------------------------------------------------------------------
// Random triangles against the exact values at each pixel centre, from the snapped positions.
//
// Error bound per pixel (u: a varying, q = u/w and r = 1/w the planes, e = 2^-24):
//   Setup computes each plane in double and rounds at0, ddx, ddy to float; the pixel evaluates
//   (at0 + ddx*dx) + ddy*dy in float. Counting one rounding per coefficient, product and sum,
//   |error| <= 4e * S with S = |at0| + |ddx*dx| + |ddy*dy|; we allow 5e * S for second-order terms
//   and the double arithmetic of setup. The anchor (at0) lies in the bounding box of the snapped
//   vertices, clipped to the viewport, so S <= termBound() over that box.
//   u = q * (1/r) adds two float roundings: |du| <= (|dq| + |u| |dr|) / r + 3e |u|.
//   Depth is one plane: |dz| <= 5e * S_z (the clamp to [0, 1] only moves it towards the exact
//   value, which lies in [0, 1]).
TEST(InterpolationPerspective, RandomTrianglesWithinFloatErrorBound) {
  const uint64_t seed = 0x1e7e9001;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  constexpr int S = 64;
  double worstRatio = 0, worstUError = 0;
  uint64_t pixels = 0;
  for (int iter = 0; iter < 120; ++iter) {
    const FixedPointFormat format =
        iter % 2 ? FixedPointFormat::d16_8() : FixedPointFormat::d24_4();
    const PipelineState state = captureState(S, S, format);
    std::vector<ShadedVertex<2>> vertices;
    for (int k = 0; k < 3; ++k) {
      // Window position partly outside the viewport, w over a ratio of 8, depth inside (0, 1).
      const double wx = -8 + 80 * u01(rng), wy = -8 + 80 * u01(rng);
      const double w = 0.5 + 3.5 * u01(rng), zNdc = -0.95 + 1.9 * u01(rng);
      const glm::dvec4 clip((wx - S / 2.0) / (S / 2.0) * w, -(wy - S / 2.0) / (S / 2.0) * w,
                            zNdc * w, w);
      // u in [0, 1]; v with a large offset, so its relative precision matters.
      vertices.push_back({glm::vec4(clip), {float(u01(rng)), float(1000.0 + u01(rng))}});
    }
    std::array<SnappedVertex, 3> v;
    for (int k = 0; k < 3; ++k) v[k] = snapVertex(vertices[k].position, state);
    const double area =
        std::abs((v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y));
    if (area < 40) continue;  // slivers: the bound holds but says little

    const Captured<2> c = drawAndCapture<2>(state, S, S, vertices, {0, 1, 2});
    const double bx0 = std::max(0.0, std::min({v[0].x, v[1].x, v[2].x}));
    const double bx1 = std::min(double(S), std::max({v[0].x, v[1].x, v[2].x}));
    const double by0 = std::max(0.0, std::min({v[0].y, v[1].y, v[2].y}));
    const double by1 = std::min(double(S), std::max({v[0].y, v[1].y, v[2].y}));
    const std::array<double, 3> invW = {v[0].invW, v[1].invW, v[2].invW};
    const std::array<double, 3> depth = {v[0].z, v[1].z, v[2].z};
    const double sR = termBound(v, invW, bx0, by0, bx1, by1);
    const double sZ = termBound(v, depth, bx0, by0, bx1, by1);
    std::array<double, 2> sQ;
    for (int k = 0; k < 2; ++k) {
      std::array<double, 3> q;
      for (int i = 0; i < 3; ++i) q[i] = double(vertices[i].varyings[k]) * invW[i];
      sQ[k] = termBound(v, q, bx0, by0, bx1, by1);
    }
    const std::string what = "iteration " + std::to_string(iter) + " " + format.name();
    int failures = 0;
    for (int y = 0; y < S; ++y) {
      for (int x = 0; x < S; ++x) {
        const size_t i = size_t(y) * S + x;
        if (c.counts[i] == 0) {
          EXPECT_TRUE(std::isnan(c.depth[i])) << what << ": shaded an uncovered pixel";
          continue;
        }
        ++pixels;
        const auto l = barycentric(v, x + 0.5, y + 0.5);
        const double r = l[0] * invW[0] + l[1] * invW[1] + l[2] * invW[2];
        for (int k = 0; k < 2; ++k) {
          const double q = l[0] * vertices[0].varyings[k] * invW[0] +
                           l[1] * vertices[1].varyings[k] * invW[1] +
                           l[2] * vertices[2].varyings[k] * invW[2];
          const double exact = q / r;
          const double bound =
              5 * kFloatEps * (sQ[k] + std::abs(exact) * sR) / r + 3 * kFloatEps * std::abs(exact);
          const double err = std::abs(c.varyings[i][k] - exact);
          worstRatio = std::max(worstRatio, err / bound);
          if (k == 0) worstUError = std::max(worstUError, err);
          if (err > bound && ++failures <= 3)
            ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") varying " << k << " "
                          << c.varyings[i][k] << ", exact " << exact << ", error " << err
                          << " > bound " << bound;
        }
        const double zExact = l[0] * depth[0] + l[1] * depth[1] + l[2] * depth[2];
        const double zErr = std::abs(c.depth[i] - zExact);
        if (zErr > 5 * kFloatEps * sZ && ++failures <= 3)
          ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") depth " << c.depth[i]
                        << ", exact " << zExact << ", error " << zErr;
        EXPECT_TRUE(c.depth[i] >= 0.0f && c.depth[i] <= 1.0f) << what;
      }
    }
    EXPECT_EQ(failures, 0) << what;
  }
  std::cout << "worst error / bound " << worstRatio << ", worst |u error| " << worstUError
            << " over " << pixels << " pixels\n";
  EXPECT_GT(pixels, 20000u) << "not enough covered pixels to mean anything";
}

// Depth is exactly 0 and 1 at vertices on the near and far planes, and extrapolating the plane
// to pixel centres just outside the vertex range must not leave [0, 1]. Window space (z given)
// and clip space (z = -w and z = w) both.
TEST(InterpolationDepth, StaysInUnitRangeAtNearAndFarPlanes) {
  constexpr int S = 48;
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    for (const PositionSpace space : {PositionSpace::Window, PositionSpace::Clip}) {
      const PipelineState state = captureState(S, S, format, space);
      std::vector<ShadedVertex<0>> vertices;
      if (space == PositionSpace::Window) {
        // A sliver-ish fan of depth 0 and 1 vertices, so the depth gradient is steep.
        vertices = {{glm::vec4(1.3f, 2.1f, 0.0f, 1.0f)},
                    {glm::vec4(46.9f, 3.7f, 1.0f, 1.0f)},
                    {glm::vec4(2.2f, 45.6f, 1.0f, 1.0f)},
                    {glm::vec4(47.1f, 44.3f, 0.0f, 1.0f)}};
      } else {
        vertices = {{glm::vec4(-0.9f, 0.95f, -1.0f, 1.0f)},
                    {glm::vec4(0.97f, 0.9f, 2.0f, 2.0f)},
                    {glm::vec4(-1.9f, -1.96f, 2.0f, 2.0f)},
                    {glm::vec4(0.5f, -0.49f, -0.5f, 0.5f)}};
      }
      const Captured<0> c = drawAndCapture<0>(state, S, S, vertices, {0, 1, 2, 3, 2, 1});
      int covered = 0, atZero = 0, atOne = 0;
      for (size_t i = 0; i < c.counts.size(); ++i) {
        if (c.counts[i] == 0) continue;
        ++covered;
        ASSERT_TRUE(c.depth[i] >= 0.0f && c.depth[i] <= 1.0f)
            << format.name() << " pixel " << i % S << ", " << i / S << " depth " << c.depth[i];
        atZero += c.depth[i] < 0.02f;
        atOne += c.depth[i] > 0.98f;
      }
      // The whole range is exercised: pixels near both ends.
      EXPECT_GT(covered, S * S / 2) << format.name();
      EXPECT_GT(atZero, 0) << format.name();
      EXPECT_GT(atOne, 0) << format.name();
    }
  }
}

// The back end interpolates the varyings of whole rows of a tile at once (interpolateRows, in
// loops the compiler vectorises); every lane must hold interpolateVaryings' bits at that pixel,
// in the baseline build and in the AVX2 one, including lanes outside a triangle where 1/w is
// extrapolated through zero (infinite or NaN values; any NaN matches any NaN).
template <int N>
void interpolateRowsBaseline(const SetupTriangle<N>& t, int x0, int y0, int r0, int r1,
                             TileVaryings<N>& out) {
  interpolateRows<N>(t, x0, y0, r0, r1, out);
}
template <int N>
[[gnu::target("avx2")]] void interpolateRowsAvx2(const SetupTriangle<N>& t, int x0, int y0,
                                                 int r0, int r1, TileVaryings<N>& out) {
  interpolateRows<N>(t, x0, y0, r0, r1, out);
}

bool sameFloat(float a, float b) {
  return (std::isnan(a) && std::isnan(b)) || std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

TEST(InterpolationRows, EveryLaneEqualsInterpolateVaryingsBitForBit) {
  std::mt19937 rng(0x70775);
  std::uniform_real_distribution<float> coefficient(-4.0f, 4.0f), offset(-2000.0f, 2000.0f);
  std::uniform_int_distribution<int> pixel(0, 4000), row(0, kTileSize - 1);
  const bool avx2 = cpuHasAvx2BackEnd();
  uint64_t lanes = 0, nonFinite = 0, pastZero = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    SetupTriangle<3> t;
    t.bounds = {pixel(rng), pixel(rng), 0, 0};
    t.bounds.x1 = t.bounds.x0 + 64;
    t.bounds.y1 = t.bounds.y0 + 64;
    // 1/w small beside its slopes in a fifth of the cases, so that it crosses zero in the tile.
    const float invWScale = iter % 5 == 0 ? 0.01f : 1.0f;
    t.invW = {std::abs(coefficient(rng)) * invWScale, coefficient(rng) * 0.01f,
              coefficient(rng) * 0.01f};
    // And exactly zero everywhere now and then: every lane infinite or NaN.
    if (iter % 97 == 0) t.invW = {0.0f, 0.0f, 0.0f};
    for (PlaneEquation& v : t.varyingsOverW)
      v = {offset(rng), coefficient(rng), coefficient(rng)};
    const int x0 = t.bounds.x0 + int(rng() % 56), y0 = t.bounds.y0 + int(rng() % 56);
    int r0 = row(rng), r1 = row(rng);
    if (r0 > r1) std::swap(r0, r1);
    ++r1;
    for (int target = 0; target < (avx2 ? 2 : 1); ++target) {
      TileVaryings<3> rows;
      if (target == 0) interpolateRowsBaseline<3>(t, x0, y0, r0, r1, rows);
      else interpolateRowsAvx2<3>(t, x0, y0, r0, r1, rows);
      for (int ly = r0; ly < r1; ++ly)
        for (int lx = 0; lx < kTileSize; ++lx) {
          Varyings<3> expected;
          interpolateVaryings<3>(t, float(x0 + lx - t.bounds.x0), float(y0 + ly - t.bounds.y0),
                                 expected);
          for (int k = 0; k < 3; ++k) {
            const float got = rows[k][ly * kTileSize + lx];
            ASSERT_TRUE(sameFloat(got, expected[k]))
                << (target ? "AVX2" : "baseline") << ", iteration " << iter << ", lane (" << lx
                << ", " << ly << ") varying " << k << ": " << got << " != " << expected[k];
            nonFinite += !std::isfinite(got);
            pastZero += t.invW.at(float(x0 + lx - t.bounds.x0), float(y0 + ly - t.bounds.y0)) < 0;
            ++lanes;
          }
        }
    }
  }
  EXPECT_GT(lanes, 1000000u);
  EXPECT_GT(nonFinite, 0u) << "no lane where 1/w is zero: infinities and NaNs are not tested";
  EXPECT_GT(pastZero, 0u) << "no lane where 1/w is negative: the extrapolation is not tested";
}

// Depth is interpolated a row of a tile at a time as well (depthLanes, SSE2); every lane must hold
// interpolateDepth's bits at its sample, clamp included: depths beyond [0, 1] clamp to the bound,
// -0 stays -0, NaN stays NaN. Baseline and AVX2 builds, with MSAA sample offsets.
template <int N>
void depthLanesBaseline(const SetupTriangle<N>& t, int x0, int y0, float ox, float oy, int r0,
                        int r1, TileLanes<float>& z) {
  depthLanes<N>(t, x0, y0, ox, oy, r0, r1, z);
}
template <int N>
[[gnu::target("avx2")]] void depthLanesAvx2(const SetupTriangle<N>& t, int x0, int y0, float ox,
                                            float oy, int r0, int r1, TileLanes<float>& z) {
  depthLanes<N>(t, x0, y0, ox, oy, r0, r1, z);
}

TEST(InterpolationRows, EveryDepthLaneEqualsInterpolateDepthBitForBit) {
  std::mt19937 rng(0xde97);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), slope(-0.02f, 0.02f);
  std::uniform_int_distribution<int> pixel(0, 4000), row(0, kTileSize - 1);
  const float kOffsets[] = {0.0f, 0.125f, -0.375f, 0.4375f};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const bool avx2 = cpuHasAvx2BackEnd();
  uint64_t lanes = 0, clampedLow = 0, clampedHigh = 0, negativeZero = 0, nans = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    SetupTriangle<0> t;
    t.bounds = {pixel(rng), pixel(rng), 0, 0};
    t.bounds.x1 = t.bounds.x0 + 64;
    t.bounds.y1 = t.bounds.y0 + 64;
    t.depth = {unit(rng) * 1.2f - 0.1f, slope(rng), slope(rng)};
    if (iter % 7 == 0) t.depth.ddx *= 100.0f;  // steep: most lanes clamp
    if (iter % 101 == 0) t.depth = {-0.0f, -0.0f, -0.0f};
    if (iter % 103 == 0) t.depth.ddy = nan;
    if (iter % 107 == 0) t.depth.ddx = inf;
    const int x0 = t.bounds.x0 + int(rng() % 56), y0 = t.bounds.y0 + int(rng() % 56);
    const float ox = kOffsets[rng() % 4], oy = kOffsets[rng() % 4];
    int r0 = row(rng), r1 = row(rng);
    if (r0 > r1) std::swap(r0, r1);
    ++r1;
    for (int target = 0; target < (avx2 ? 2 : 1); ++target) {
      TileLanes<float> z;
      if (target == 0) depthLanesBaseline<0>(t, x0, y0, ox, oy, r0, r1, z);
      else depthLanesAvx2<0>(t, x0, y0, ox, oy, r0, r1, z);
      for (int ly = r0; ly < r1; ++ly)
        for (int lx = 0; lx < kTileSize; ++lx) {
          const float dx = float(x0 - t.bounds.x0) + ox + float(lx);
          const float dy = float(y0 - t.bounds.y0) + oy + float(ly);
          const float expected = interpolateDepth(t, dx, dy);
          const float got = z[ly * kTileSize + lx];
          ASSERT_TRUE(sameFloat(got, expected))
              << (target ? "AVX2" : "baseline") << ", iteration " << iter << ", lane (" << lx
              << ", " << ly << "): " << got << " != " << expected;
          const float raw = t.depth.at(dx, dy);
          clampedLow += raw < 0.0f;
          clampedHigh += raw > 1.0f;
          negativeZero += std::bit_cast<uint32_t>(got) == 0x80000000u;
          nans += std::isnan(got);
          ++lanes;
        }
    }
  }
  EXPECT_GT(lanes, 500000u);
  EXPECT_GT(clampedLow, 0u);
  EXPECT_GT(clampedHigh, 0u);
  EXPECT_GT(negativeZero, 0u) << "-0 is not tested";
  EXPECT_GT(nans, 0u) << "NaN is not tested";
}

}  // namespace
}  // namespace rast
