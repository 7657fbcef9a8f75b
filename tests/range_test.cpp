// Range limits of every fixed-point precision, F = 1..8 fraction bits: the largest viewport and
// coordinates each format represents and just beyond, huge triangles against an exact integer
// reference, sub-pixel slivers, collinear and repeated vertices, w around zero, and NaN and
// infinity in every coordinate. Expected counts are exact, and the statistics say why.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"

namespace rast {
namespace {

struct PositionVS {
  using Vertex = glm::vec4;
  static constexpr int kVaryings = 0;
  ShadedVertex<0> operator()(const glm::vec4& p) const { return {p, {}}; }
};

PipelineState countingState(Viewport vp, FixedPointFormat format, PositionSpace space) {
  PipelineState s;
  s.viewport = vp;
  s.format = format;
  s.positionSpace = space;
  s.depth.compare = CompareOp::Always;  // every covered sample counts
  s.depth.write = false;
  return s;
}

struct Drawn {
  Status status = Status::ok();
  std::vector<uint32_t> counts;
  PipelineStatistics stats;
};

Drawn drawCounts(const PipelineState& state, int width, int height,
                 const std::vector<glm::vec4>& vertices, const std::vector<uint32_t>& indices) {
  Framebuffer fb(width, height, true);
  Drawn d;
  const PositionVS vs;
  const ConstantColorShader ps;
  d.status = draw(fb, state, DrawCall<PositionVS, ConstantColorShader>{vertices, indices, vs, ps},
                  d.stats);
  d.counts = fb.countPlane();
  return d;
}

uint64_t sum(const std::vector<uint32_t>& v) {
  uint64_t s = 0;
  for (uint32_t c : v) s += c;
  return s;
}

class EveryPrecision : public ::testing::TestWithParam<int> {
 protected:
  FixedPointFormat format() const { return FixedPointFormat::withFractionBits(GetParam()); }
};

std::string precisionName(const ::testing::TestParamInfo<int>& info) {
  return std::string("F").append(std::to_string(info.param));  // not "F" + ...: GCC 12 -Wrestrict
}

// ---------------------------------------------------------------------------------------------
// The limits of each format, stated here independently of fixed_point.h: F fraction bits leave
// 28 - F integer bits (16 for F = 8, Direct3D's 16.8), the guard band is a quarter of the
// representable range, 2^(I-2) pixels, and the largest snapped coordinate 2^(I+F-2) subpixels.

double expectedGuardBand(int f) { return std::ldexp(1.0, (f == 8 ? 16 : 28 - f) - 2); }

TEST_P(EveryPrecision, LimitsOfTheFormat) {
  const int f = GetParam();
  const FixedPointFormat fmt = format();
  EXPECT_EQ(fmt.integerBits + fmt.fractionBits, f == 8 ? 24 : 28);
  EXPECT_EQ(fmt.guardBandPixels(), expectedGuardBand(f));
  EXPECT_EQ(double(fmt.guardBandSubpixels()), std::ldexp(expectedGuardBand(f), f));
  // The bound behind exact int64 edge functions: 2 * (2 * G)^2 < 2^63 with G in subpixels.
  EXPECT_LE(fmt.guardBandSubpixels(), 1 << 26);
}

// The largest viewport is accepted and renders; one pixel more on any side is a clear error and
// draws nothing.
TEST_P(EveryPrecision, ViewportAtTheGuardBandAndOnePixelBeyond) {
  const FixedPointFormat fmt = format();
  const int g = int(expectedGuardBand(GetParam()));
  const std::vector<glm::vec4> quad = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
  constexpr int W = 24, H = 16;
  for (const Viewport vp : {Viewport{-g, -g, 2 * g, 2 * g}, Viewport{0, 0, g, g},
                            Viewport{-g, 0, g + W, H}}) {
    const Drawn d = drawCounts(countingState(vp, fmt, PositionSpace::Clip), W, H, quad, indices);
    ASSERT_TRUE(d.status.isOk()) << fmt.name() << ": " << d.status.message();
    EXPECT_EQ(d.counts, std::vector<uint32_t>(W * H, 1u)) << fmt.name() << " viewport " << vp.x;
    EXPECT_EQ(d.stats.fragmentsWritten, uint64_t(W * H));
  }
  const std::string range = "exceeds the " + fmt.name() + " fixed-point range of +-" +
                            std::to_string(g) + " pixels";
  for (const Viewport vp : {Viewport{-g - 1, 0, 8, 8}, Viewport{0, -g - 1, 8, 8},
                            Viewport{g - 7, 0, 8, 8}, Viewport{0, g - 7, 8, 8},
                            Viewport{-g, -g, 2 * g + 1, 8}, Viewport{0, 0, g + 1, 8},
                            Viewport{std::numeric_limits<int>::min(), 0, 8, 8},
                            Viewport{std::numeric_limits<int>::max() - 3, 0, 8, 8},
                            Viewport{0, 0, std::numeric_limits<int>::max(), 8}}) {
    const Drawn d = drawCounts(countingState(vp, fmt, PositionSpace::Clip), W, H, quad, indices);
    ASSERT_FALSE(d.status.isOk()) << fmt.name() << " viewport " << vp.x << ", " << vp.y << " "
                                  << vp.width << "x" << vp.height;
    EXPECT_NE(d.status.message().find(range), std::string::npos) << d.status.message();
    EXPECT_EQ(sum(d.counts), 0u);
    EXPECT_TRUE(d.stats == PipelineStatistics{});
  }
}

// Set-up triangles keep their bounds in 16 bits (setup.h): the widest and tallest framebuffers a
// draw accepts are covered to their last pixel (bounds reaching 32768, which a signed 16-bit
// bound would turn negative), and one pixel more is a clear error that draws nothing.
TEST(FramebufferSide, LargestAcceptedAndOneBeyond) {
  const std::vector<glm::vec4> quad = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
  const FixedPointFormat fmt = FixedPointFormat::withFractionBits(4);
  const int side = kMaxFramebufferSide;
  for (const auto& [w, h] : {std::pair{side, 3}, std::pair{3, side}}) {
    const Drawn d =
        drawCounts(countingState({0, 0, w, h}, fmt, PositionSpace::Clip), w, h, quad, indices);
    ASSERT_TRUE(d.status.isOk()) << d.status.message();
    EXPECT_EQ(d.counts, std::vector<uint32_t>(size_t(w) * h, 1u)) << w << "x" << h;
  }
  for (const auto& [w, h] : {std::pair{side + 1, 3}, std::pair{3, side + 1}}) {
    const Drawn d =
        drawCounts(countingState({0, 0, w, h}, fmt, PositionSpace::Clip), w, h, quad, indices);
    ASSERT_FALSE(d.status.isOk());
    EXPECT_NE(d.status.message().find("exceeds 32768 pixels a side"), std::string::npos)
        << d.status.message();
    EXPECT_EQ(sum(d.counts), 0u);
    EXPECT_TRUE(d.stats == PipelineStatistics{});
  }
}

// A window-space quad with corners at +-c covers each pixel of the framebuffer once, whether c is
// the largest coordinate the format represents (no clipping), the float just below it, the float
// just above it, or far beyond (the guard band clips), up to the largest float. The diagonal runs through every
// sample (k + 0.5, k + 0.5): the fill rule gives each to exactly one of the two triangles.
TEST_P(EveryPrecision, VerticesAtTheLargestCoordinateAndBeyond) {
  const FixedPointFormat fmt = format();
  const double g = fmt.guardBandPixels();
  const double below = std::nextafter(float(g), 0.0f), above = std::nextafter(float(g), 1e30f);
  constexpr int W = 40, H = 24;
  struct Case {
    double c;
    uint64_t clipped;
  };
  const Case cases[] = {{g, 0},
                        {below, 0},
                        {above, 2},
                        {2 * g, 2},
                        {0x1p66, 2},
                        {double(std::numeric_limits<float>::max()), 2}};
  for (const Case& k : cases) {
    const float c = float(k.c);
    ASSERT_EQ(double(c), k.c) << "the corner must be exact in float";
    const std::vector<glm::vec4> quad = {{-c, -c, 0.5f, 1}, {c, -c, 0.5f, 1}, {c, c, 0.5f, 1},
                                         {-c, c, 0.5f, 1}};
    for (const std::vector<uint32_t>& indices :
         {std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, std::vector<uint32_t>{0, 2, 1, 0, 3, 2}}) {
      const Drawn d = drawCounts(countingState({0, 0, W, H}, fmt, PositionSpace::Window), W, H,
                                 quad, indices);
      const std::string what = fmt.name() + " corner " + std::to_string(k.c);
      ASSERT_TRUE(d.status.isOk()) << what << ": " << d.status.message();
      EXPECT_EQ(d.counts, std::vector<uint32_t>(W * H, 1u)) << what;
      EXPECT_EQ(d.stats.clipClipped, k.clipped) << what;
      EXPECT_EQ(d.stats.clipNonFinite + d.stats.clipDegenerate + d.stats.setupZeroArea, 0u) << what;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Exact integer reference: vertices on the subpixel grid snap to themselves, so coverage is
// decided by the sign of exact (128-bit) edge functions with the top-left rule.

struct SubPoint {
  int64_t x, y;
};

__int128 orient(SubPoint a, SubPoint b, SubPoint c) {
  return __int128(b.x - a.x) * (c.y - a.y) - __int128(b.y - a.y) * (c.x - a.x);
}

bool referenceCovers(const std::array<SubPoint, 3>& v, SubPoint s) {
  const __int128 o = orient(v[0], v[1], v[2]);
  if (o == 0) return false;
  for (int i = 0; i < 3; ++i) {
    const SubPoint p = v[i], q = v[(i + 1) % 3], r = v[(i + 2) % 3];
    const __int128 e = orient(p, q, s);
    if (e != 0) {
      if ((e > 0) != (o > 0)) return false;
      continue;
    }
    const bool top = p.y == q.y && r.y > p.y;  // horizontal, interior below (y down)
    const bool left = p.y != q.y && ((p.y - q.y > 0) == (o > 0));  // interior to the right
    if (!top && !left) return false;
  }
  return true;
}

// Draws window-space triangles whose vertices lie on the subpixel grid and compares every pixel
// with the reference. Returns the number of covered samples.
uint64_t expectExactCoverage(const std::vector<std::array<SubPoint, 3>>& triangles,
                             FixedPointFormat fmt, int width, int height, const std::string& what) {
  const double unit = fmt.subpixelsPerPixel();
  std::vector<glm::vec4> v;
  std::vector<uint32_t> idx;
  std::vector<uint32_t> reference(size_t(width) * height, 0);
  const int64_t half = fmt.subpixelsPerPixel() / 2;
  for (const auto& t : triangles) {
    for (const SubPoint& p : t) {
      const glm::vec4 f(float(double(p.x) / unit), float(double(p.y) / unit), 0.5f, 1.0f);
      EXPECT_EQ(double(f.x) * unit, double(p.x)) << what << ": not exact in float";
      EXPECT_EQ(double(f.y) * unit, double(p.y)) << what << ": not exact in float";
      idx.push_back(uint32_t(v.size()));
      v.push_back(f);
    }
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        reference[size_t(y) * width + x] +=
            referenceCovers(t, {x * fmt.subpixelsPerPixel() + half, y * fmt.subpixelsPerPixel() + half});
  }
  const Drawn d =
      drawCounts(countingState({0, 0, width, height}, fmt, PositionSpace::Window), width, height, v, idx);
  EXPECT_TRUE(d.status.isOk()) << what << ": " << d.status.message();
  int wrong = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      if (d.counts[i] != reference[i] && ++wrong <= 3)
        ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") count " << d.counts[i]
                      << ", exact reference " << reference[i];
    }
  EXPECT_EQ(wrong, 0) << what;
  EXPECT_EQ(d.stats.clipClipped, 0u) << what << ": vertices inside the guard band are not clipped";
  return sum(reference);
}

// Huge triangles: vertices anywhere in the guard band (at its corners, on its sides, or random),
// so edges are up to 2^27 subpixels long and cross the 64x48 framebuffer at random slopes, and
// ties where an edge passes through a sample. Every precision takes its int64 paths here.
TEST_P(EveryPrecision, HugeTrianglesMatchExactReference) {
  const FixedPointFormat fmt = format();
  const int64_t g = fmt.guardBandSubpixels();
  const int64_t unit = fmt.subpixelsPerPixel();
  const uint64_t seed = 0x7a46e000 + GetParam();
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int64_t> anywhere(-g, g);
  constexpr int W = 64, H = 48;
  // Window coordinates arrive as floats: far from the origin, the subpixels a float can hold.
  auto inFloat = [](int64_t v) { return int64_t(float(v)); };
  auto vertex = [&]() -> SubPoint {
    switch (rng() % 4) {
      case 0: return {rng() % 2 ? g : -g, rng() % 2 ? g : -g};           // a corner
      case 1: return {rng() % 2 ? g : -g, inFloat(anywhere(rng))};       // a side
      case 2: return {int64_t(rng() % (W * unit)), int64_t(rng() % (H * unit))};  // on screen
      default: return {inFloat(anywhere(rng)), inFloat(anywhere(rng))};
    }
  };
  uint64_t covered = 0;
  for (int iter = 0; iter < 60; ++iter) {
    std::array<SubPoint, 3> t = {vertex(), vertex(), vertex()};
    // One edge through the sample (8.5, 8.5) and its mirror through the image: ties on it.
    if (iter % 3 == 0) {
      const SubPoint s{8 * unit + unit / 2, 8 * unit + unit / 2};
      const int64_t dx = int64_t(rng() % 2000) - 1000, dy = int64_t(rng() % 2000) - 1000;
      // A power of two up to 2^14, so s + d * k (at most 24 significant bits) is a float.
      int64_t k = int64_t{1} << 14;
      while (k > 1 && std::max(std::abs(dx), std::abs(dy)) * k > g - s.x) k /= 2;
      t[0] = {s.x + dx * k, s.y + dy * k};
      t[1] = {s.x - dx * k, s.y - dy * k};
    }
    covered += expectExactCoverage({t}, fmt, W, H, fmt.name() + " huge " + std::to_string(iter));
    if (HasFailure()) return;
  }
  EXPECT_GT(covered, uint64_t(60 * W * H / 8)) << "not vacuous: huge triangles cover much";
}

// Sub-pixel triangles and slivers, with areas far below 1/256 pixel where the format allows: on
// samples, beside them, along a sample row (top edge: covered; bottom edge: not).
TEST_P(EveryPrecision, SubPixelAndSliverTriangles) {
  const FixedPointFormat fmt = format();
  const int64_t u = fmt.subpixelsPerPixel(), h = u / 2;
  constexpr int W = 40, H = 16;
  auto centre = [&](int x, int y) { return SubPoint{x * u + h, y * u + h}; };
  struct Case {
    std::string name;
    std::array<SubPoint, 3> t;
    uint64_t samples;
  };
  const SubPoint c = centre(5, 6);
  const std::vector<Case> cases = {
      // One subpixel around a sample, clockwise: the sample is inside (area 1 subpixel^2).
      {"tiny around a sample", {SubPoint{c.x - 1, c.y - 1}, SubPoint{c.x + 1, c.y}, SubPoint{c.x, c.y + 1}}, 1},
      // The same, counter-clockwise: the same coverage.
      {"tiny around a sample, ccw", {SubPoint{c.x - 1, c.y - 1}, SubPoint{c.x, c.y + 1}, SubPoint{c.x + 1, c.y}}, 1},
      // Beside a sample: nothing.
      {"tiny beside a sample", {SubPoint{c.x + 1, c.y + 1}, SubPoint{c.x + 2, c.y + 1}, SubPoint{c.x + 1, c.y + 2}}, 0},
      // A sample on its left edge (vertical, interior right): covered; on its right edge: not.
      {"sample on a left edge", {SubPoint{c.x, c.y - 1}, SubPoint{c.x + 1, c.y + 1}, SubPoint{c.x, c.y + 1}}, 1},
      {"sample on a right edge", {SubPoint{c.x, c.y - 1}, SubPoint{c.x, c.y + 1}, SubPoint{c.x - 1, c.y + 1}}, 0},
      // A sample at a vertex shared by a top and a left edge: covered; at the bottom-right: not.
      {"sample at a top-left vertex", {c, SubPoint{c.x + 1, c.y}, SubPoint{c.x, c.y + 1}}, 1},
      {"sample at a bottom-right vertex", {c, SubPoint{c.x - 1, c.y}, SubPoint{c.x, c.y - 1}}, 0},
      // A sliver one subpixel high along the sample row y = 8.5, x from 1 to 30: its top edge
      // holds the samples 1.5 .. 29.5.
      {"sliver below a sample row", {SubPoint{1 * u, 8 * u + h}, SubPoint{30 * u, 8 * u + h}, SubPoint{30 * u, 8 * u + h + 1}}, 29},
      // The same sliver above the row: the row is its bottom edge, nothing is covered.
      {"sliver above a sample row", {SubPoint{1 * u, 8 * u + h}, SubPoint{30 * u, 8 * u + h - 1}, SubPoint{30 * u, 8 * u + h}}, 0},
      // A sliver along a sample column x = 3.5 from y = 1 to 14: its left edge holds 13 samples.
      {"sliver right of a sample column", {SubPoint{3 * u + h, 1 * u}, SubPoint{3 * u + h + 1, 14 * u}, SubPoint{3 * u + h, 14 * u}}, 13},
      {"sliver left of a sample column", {SubPoint{3 * u + h, 1 * u}, SubPoint{3 * u + h, 14 * u}, SubPoint{3 * u + h - 1, 14 * u}}, 0},
      // A long diagonal sliver whose left edge runs through the samples (k + 0.5, k + 0.5),
      // k = 0..14: it owns k = 1..13; the end samples are vertices where a bottom or right edge
      // meets it, which do not own them.
      {"diagonal sliver", {SubPoint{h, h}, SubPoint{14 * u + h + 1, 14 * u + h}, SubPoint{14 * u + h, 14 * u + h}}, 13},
  };
  for (const Case& k : cases) {
    const uint64_t n = expectExactCoverage({k.t}, fmt, W, H, fmt.name() + " " + k.name);
    EXPECT_EQ(n, k.samples) << fmt.name() << " " << k.name;
  }
  // Area below 1/256 pixel when the grid allows it (F >= 5): the tiny triangles above.
  if (fmt.fractionBits >= 5) {
    EXPECT_LT(1.0 / double(u * u), 1.0 / 256);
  }
}

// Triangles of float vertices smaller than a subpixel snap to a point, a segment or a tiny
// triangle: zero-area ones are counted as such and draw nothing.
TEST_P(EveryPrecision, CollinearAndRepeatedVertices) {
  const FixedPointFormat fmt = format();
  const float quarter = float(std::ldexp(1.0, -fmt.fractionBits - 2));  // a quarter subpixel
  constexpr int W = 32, H = 16;
  const std::vector<std::array<glm::vec2, 3>> zeroArea = {
      {glm::vec2(5.5f, 5.5f), glm::vec2(5.5f, 5.5f), glm::vec2(5.5f, 5.5f)},   // one point
      {glm::vec2(1, 1), glm::vec2(1, 1), glm::vec2(20, 9)},                    // repeated
      {glm::vec2(1, 1), glm::vec2(20, 9), glm::vec2(20, 9)},
      {glm::vec2(1, 1), glm::vec2(10.5f, 5), glm::vec2(20, 9)},                // collinear
      {glm::vec2(0.5f, 3.5f), glm::vec2(31.5f, 3.5f), glm::vec2(12.5f, 3.5f)}, // along a sample row
      {glm::vec2(2.5f, 0), glm::vec2(2.5f, 16), glm::vec2(2.5f, 7)},           // along a column
      // Collinear only after snapping: the middle vertex a quarter subpixel off the line.
      {glm::vec2(1, 2), glm::vec2(11, 7 + quarter), glm::vec2(21, 12)},
      {glm::vec2(4.5f, 4.5f), glm::vec2(4.5f + quarter, 4.5f), glm::vec2(4.5f, 4.5f + quarter)},
  };
  std::vector<glm::vec4> v;
  std::vector<uint32_t> idx;
  for (const auto& t : zeroArea)
    for (const glm::vec2 p : t) {
      idx.push_back(uint32_t(v.size()));
      v.push_back({p, 0.5f, 1});
    }
  const Drawn d = drawCounts(countingState({0, 0, W, H}, fmt, PositionSpace::Window), W, H, v, idx);
  ASSERT_TRUE(d.status.isOk());
  EXPECT_EQ(d.stats.inputTriangles, zeroArea.size());
  EXPECT_EQ(d.stats.setupZeroArea, zeroArea.size()) << fmt.name();
  EXPECT_EQ(d.stats.setupTriangles, 0u);
  EXPECT_EQ(sum(d.counts), 0u);
}

// ---------------------------------------------------------------------------------------------
// w around zero. The apex (a, 1, 0, w) with w -> 0 is the point at infinity in direction (a, 1):
// the triangle tends to the strip between the lines from NDC (-1, -1) and (1, -1) in that
// direction. With w = +-1e-30, +-1e-20, +-0 the sides are within 1e-18 px of those lines, no sample
// is within 0.05 px of them, so the coverage is the strip's, exactly; the near plane and the guard
// band clip the triangle every time, and nothing is degenerate.
TEST_P(EveryPrecision, ApexAtWJustAboveAndBelowZero) {
  const FixedPointFormat fmt = format();
  constexpr int W = 32, H = 32;
  for (const double a : {0.0, 0.5, -0.25}) {
    // Expected: inside the strip { -1 <= x - a (y + 1) <= 1 } in NDC, above y = -1.
    std::vector<uint32_t> expected(W * H);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const double nx = (x + 0.5) / (W / 2) - 1, ny = 1 - (y + 0.5) / (H / 2);
        const double s = nx - a * (ny + 1);
        ASSERT_GT(std::min(std::abs(s - 1), std::abs(s + 1)) * W / 2, 0.05);
        expected[size_t(y) * W + x] = std::abs(s) < 1 ? 1 : 0;
      }
    for (const float w : {1e-30f, -1e-30f, 1e-20f, -1e-20f, 0.0f, -0.0f}) {
      const std::vector<glm::vec4> v = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {float(a), 1, 0, w}};
      const std::string what = fmt.name() + " direction " + std::to_string(a) + " w " +
                               std::to_string(w) + (std::signbit(w) ? " (negative)" : "");
      for (const std::vector<uint32_t>& idx : {std::vector<uint32_t>{0, 1, 2}, std::vector<uint32_t>{0, 2, 1}}) {
        const Drawn d =
            drawCounts(countingState({0, 0, W, H}, fmt, PositionSpace::Clip), W, H, v, idx);
        ASSERT_TRUE(d.status.isOk());
        EXPECT_EQ(d.counts, expected) << what;
        EXPECT_EQ(d.stats.clipClipped, 1u) << what;
        EXPECT_EQ(d.stats.clipNonFinite + d.stats.clipDegenerate, 0u) << what;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// NaN and infinity in each coordinate of each vertex, in clip and in window space: the triangle
// is dropped and counted as non-finite, and the others are drawn as if it were absent.
TEST_P(EveryPrecision, NaNAndInfinityInEveryCoordinate) {
  const FixedPointFormat fmt = format();
  constexpr int W = 24, H = 16;
  const float bad[] = {std::numeric_limits<float>::quiet_NaN(),
                       std::numeric_limits<float>::infinity(),
                       -std::numeric_limits<float>::infinity()};
  for (const PositionSpace space : {PositionSpace::Clip, PositionSpace::Window}) {
    const bool window = space == PositionSpace::Window;
    // Two good triangles covering the framebuffer, and one that will hold the bad vertex.
    const std::vector<glm::vec4> good =
        window ? std::vector<glm::vec4>{{0, 0, 0.5f, 1}, {24, 0, 0.5f, 1}, {24, 16, 0.5f, 1}, {0, 16, 0.5f, 1}}
               : std::vector<glm::vec4>{{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
    const std::vector<uint32_t> goodIdx = {0, 1, 2, 0, 2, 3};
    for (int corner = 0; corner < 3; ++corner)
      for (int coord = 0; coord < 4; ++coord)
        for (const float b : bad) {
          std::vector<glm::vec4> v = good;
          glm::vec4 p = good[1];
          p[coord] = b;
          v.push_back(p);  // index 4
          std::vector<uint32_t> idx = {0, 1, 2};
          std::array<uint32_t, 3> badTri = {0, 2, 3};
          badTri[size_t(corner)] = 4;
          idx.insert(idx.end(), badTri.begin(), badTri.end());
          const Drawn d = drawCounts(countingState({0, 0, W, H}, fmt, space), W, H, v, idx);
          const std::string what = fmt.name() + (window ? " window" : " clip") + " vertex " +
                                   std::to_string(corner) + " coordinate " +
                                   std::to_string(coord) + " = " + std::to_string(b);
          ASSERT_TRUE(d.status.isOk()) << what;
          EXPECT_EQ(d.stats.inputTriangles, 2u) << what;
          EXPECT_EQ(d.stats.clipNonFinite, 1u) << what;
          EXPECT_EQ(d.stats.clipOutputTriangles, 1u) << what;
          const Drawn alone = drawCounts(countingState({0, 0, W, H}, fmt, space), W, H, good,
                                         {0, 1, 2});
          EXPECT_EQ(d.counts, alone.counts) << what;
          EXPECT_EQ(sum(d.counts), uint64_t(W * H / 2)) << what;  // one triangle of the quad
        }
    const Drawn all = drawCounts(countingState({0, 0, W, H}, fmt, space), W, H, good, goodIdx);
    EXPECT_EQ(all.counts, std::vector<uint32_t>(W * H, 1u));
  }
}

INSTANTIATE_TEST_SUITE_P(Range, EveryPrecision, ::testing::Range(1, 9), precisionName);

// ---------------------------------------------------------------------------------------------
// The command-line tool takes precisions 1..8: a 16x16 window-space square of two triangles
// covers its 256 samples once, and the statistics say so; 0 and 9 are refused.
TEST(RangeTool, EverySubpixelPrecision) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("range_tool_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "square.txt") << "0 0 0.5  16 0 0.5  0 16 0.5\n16 0 0.5  16 16 0.5  0 16 0.5\n";
  }
  // The pipeline tests above cover every precision; here the option's ends and its refusals.
  for (const int f : {0, 1, 7, 9}) {
    const std::filesystem::path stats = dir / ("stats" + std::to_string(f) + ".json");
    const std::string command = std::string(RASTERIZE_TOOL) + " " + (dir / "square.txt").string() +
                                " --width 16 --height 16 --depth-compare always --subpixel-bits " +
                                std::to_string(f) + " --stats " + stats.string() + " 2>/dev/null";
    const int status = std::system(command.c_str());
    if (f == 0 || f == 9) {
      EXPECT_NE(status, 0) << "--subpixel-bits " << f << " must be refused";
      continue;
    }
    ASSERT_EQ(status, 0) << command;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
    EXPECT_EQ(j["raster.samples_covered"], 256) << f;
    EXPECT_EQ(j["merge.fragments_written"], 256) << f;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rast
