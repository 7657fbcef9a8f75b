// Depth formats (pipeline/depth_format.h): the quantisation is exact, the merge stage compares and
// writes quantised depths, and two planes resolve exactly as the resolution formula says.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "pipeline/depth_format.h"
#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

constexpr DepthFormat kFormats[] = {DepthFormat::Float32, DepthFormat::Unorm24,
                                    DepthFormat::Unorm16};

// Every level k maps to the float nearest to k / N, strictly increasing, and back to k.
TEST(DepthFormat, UnormLevelsAreNearestFloatsInOrder) {
  for (const DepthFormat format : {DepthFormat::Unorm16, DepthFormat::Unorm24}) {
    const int bits = unormBits(format);
    const uint32_t n = (uint32_t{1} << bits) - 1;
    float previous = -1.0f;
    int wrong = 0;
    for (uint32_t k = 0; k <= n; ++k) {
      const long double exact = (long double)k / n;  // 64-bit significand: an independent check
      const float q = quantizeDepth(format, float(exact));
      const bool nearest = std::abs((long double)q - exact) <=
                               std::abs((long double)std::nextafter(q, 2.0f) - exact) &&
                           std::abs((long double)q - exact) <=
                               std::abs((long double)std::nextafter(q, -1.0f) - exact);
      const bool ok = nearest && q > previous && unormLevel(q, bits) == double(k) &&
                      quantizeDepth(format, q) == q;
      if (!ok && ++wrong <= 5)
        ADD_FAILURE() << depthFormatName(format) << " level " << k << " -> " << q;
      previous = q;
    }
    EXPECT_EQ(wrong, 0) << depthFormatName(format);
    EXPECT_EQ(quantizeDepth(format, 0.0f), 0.0f);
    EXPECT_EQ(quantizeDepth(format, 1.0f), 1.0f);
  }
}

// Arbitrary floats (and out-of-range and NaN depths) go to the correctly rounded level.
TEST(DepthFormat, QuantisesToTheNearestLevelTiesToEven) {
  std::mt19937_64 rng(0xde9f0001);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const DepthFormat format : {DepthFormat::Unorm16, DepthFormat::Unorm24}) {
    const int bits = unormBits(format);
    const long double n = (long double)((uint32_t{1} << bits) - 1);
    for (int i = 0; i < 200000; ++i) {
      const float z = i % 3 ? u(rng) : std::ldexp(u(rng), -int(rng() % 30));  // small depths too
      const long double scaled = (long double)z * n;  // exact: 48 bits
      const double k = unormLevel(z, bits);
      ASSERT_LE(std::abs(scaled - k), 0.5L) << z;
      if (std::abs(scaled - k) == 0.5L) {
        ASSERT_EQ(std::fmod(k, 2.0), 0.0) << z;
      }
    }
    EXPECT_EQ(quantizeDepth(format, -0.25f), 0.0f);
    EXPECT_EQ(quantizeDepth(format, 1.5f), 1.0f);
    EXPECT_EQ(quantizeDepth(format, NAN), 0.0f);
  }
  EXPECT_EQ(quantizeDepth(DepthFormat::Float32, 0.3f), 0.3f);
}

// ---------------------------------------------------------------------------------------------
// Through the pipeline: full-viewport planes facing the camera, in window space so that each
// plane's depth reaches the merge stage as exactly the float given (a constant plane has zero
// gradients), and the quantisation is all that happens to it.

constexpr int kSize = 24;

struct Scene {
  Framebuffer fb{kSize, kSize, true};
  PipelineState state;
};

Scene makeScene(DepthFormat format, bool reversed) {
  Scene s;
  s.state.viewport = {0, 0, kSize, kSize};
  s.state.positionSpace = PositionSpace::Window;
  s.state.depth.compare = reversed ? CompareOp::Greater : CompareOp::Less;
  s.state.depth.format = format;
  s.fb.clear(glm::vec4(0, 0, 0, 1), reversed ? 0.0f : 1.0f);
  return s;
}

void drawPlane(Scene& s, float depth, glm::vec4 color) {
  const float e = float(kSize);
  const std::vector<WindowVertex> v = {{{0, 0, depth}}, {{e, 0, depth}}, {{e, e, depth}}, {{0, e, depth}}};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
  const WindowSpaceVertexShader vs;
  const ConstantColorShader ps{color};
  PipelineStatistics stats;
  const Status st =
      draw(s.fb, s.state, DrawCall<WindowSpaceVertexShader, ConstantColorShader>{v, idx, vs, ps}, stats);
  ASSERT_TRUE(st.isOk()) << st.message();
}

TEST(DepthFormat, MergeStoresAndComparesQuantisedDepth) {
  for (const DepthFormat format : kFormats) {
    for (const bool early : {true, false}) {
      Scene s = makeScene(format, false);
      s.state.depth.early = early;
      // A unorm24 level in [1/8, 1/4), where floats are 2^-26 apart, a quarter of its step.
      const float z = quantizeDepth(DepthFormat::Unorm24, 0.2f);
      drawPlane(s, z, glm::vec4(1, 0, 0, 1));
      for (float stored : s.fb.depthPlane()) ASSERT_EQ(stored, quantizeDepth(format, z));
      // The next float is a different float32 depth but the same unorm level.
      const float above = std::nextafter(z, 1.0f);
      ASSERT_EQ(unormLevel(above, 24), unormLevel(z, 24));
      ASSERT_EQ(unormLevel(above, 16), unormLevel(z, 16));
      drawPlane(s, above, glm::vec4(0, 1, 0, 1));
      const PackedColor red = packColor(glm::vec4(1, 0, 0, 1));
      for (PackedColor c : s.fb.colorPlane()) ASSERT_EQ(c, red) << depthFormatName(format);
      s.state.depth.compare = CompareOp::LessEqual;
      drawPlane(s, above, glm::vec4(0, 1, 0, 1));
      const PackedColor expected = format == DepthFormat::Float32 ? red : packColor(glm::vec4(0, 1, 0, 1));
      for (PackedColor c : s.fb.colorPlane()) ASSERT_EQ(c, expected) << depthFormatName(format);
    }
  }
}

// Draws the farther plane, then the nearer, and returns how many pixels the nearer one won.
int nearerWins(DepthFormat format, bool reversed, float nearDepth, float farDepth) {
  Scene s = makeScene(format, reversed);
  drawPlane(s, farDepth, glm::vec4(1, 0, 0, 1));
  drawPlane(s, nearDepth, glm::vec4(0, 1, 0, 1));
  const PackedColor green = packColor(glm::vec4(0, 1, 0, 1));
  int won = 0;
  for (PackedColor c : s.fb.colorPlane()) won += c == green;
  return won;
}

// Two parallel planes at eye distance d and d + s. A separation s just above the formula's
// resolution resolves at every pixel; well below it (s / 8), with the nearer plane's depth placed
// on a quantisation level (the most favourable place), it resolves at none.
TEST(DepthFormat, ZFightingMatchesTheResolutionFormula) {
  const int all = kSize * kSize;
  std::printf("%-8s %-8s %8s %14s\n", "format", "depth", "d", "resolution");
  for (const bool reversed : {false, true}) {
    const PerspectiveDepth projection{0.1, 100.0, reversed};
    for (const DepthFormat format : kFormats) {
      for (const double d : {0.5, 2.0, 10.0, 50.0, 90.0}) {
        const double resolution = depthResolution(format, projection, d);
        std::printf("%-8s %-8s %8.1f %14.6g\n", std::string(depthFormatName(format)).c_str(),
                    reversed ? "reversed" : "standard", d, resolution);
        const std::string what = std::string(depthFormatName(format)) +
                                 (reversed ? " reversed" : " standard") + " at d = " + std::to_string(d);
        // Just above: resolved everywhere.
        const double s = 1.05 * resolution;
        EXPECT_EQ(nearerWins(format, reversed, float(projection.windowDepth(d)),
                             float(projection.windowDepth(d + s))),
                  all)
            << what;
        // Well below, at a level: resolved nowhere. The level nearest to d's depth.
        const float level = quantizeDepth(format, float(projection.windowDepth(d)));
        const double dLevel = projection.distanceAt(level);
        EXPECT_EQ(nearerWins(format, reversed, level,
                             float(projection.windowDepth(dLevel + resolution / 8))),
                  0)
            << what;
      }
    }
  }
  // The formula itself, at one point (n = 0.1, f = 100, d = 10): the depth slope is
  // f n / ((f - n) d^2) = 1.001e-3 per unit; unorm16's step 1/65535 plus the float spacing at
  // z = 0.991 (2^-24), 1.53186e-5, over it: 1.5303e-2 units.
  EXPECT_NEAR(depthResolution(DepthFormat::Unorm16, {0.1, 100.0, false}, 10.0), 1.5303e-2, 1e-6);
  // Reversed float depth is far finer than standard far from the eye (500 times at d = 50, where
  // the reversed depth is 1e-3 and its floats 2^-33 apart); unorm does not care.
  const PerspectiveDepth standard{0.1, 100.0, false}, reversedDepth{0.1, 100.0, true};
  EXPECT_LT(depthResolution(DepthFormat::Float32, reversedDepth, 50.0),
            depthResolution(DepthFormat::Float32, standard, 50.0) / 100);
  EXPECT_NEAR(depthResolution(DepthFormat::Unorm16, reversedDepth, 50.0),
              depthResolution(DepthFormat::Unorm16, standard, 50.0),
              depthResolution(DepthFormat::Unorm16, standard, 50.0) * 0.01);
}

}  // namespace
}  // namespace rast
