// The exact reference rasterizer (reference/exact_rasterizer.h) on its own, and the pipeline's
// coverage against it bit for bit, at every subpixel precision 1..8.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "reference/exact_rasterizer.h"
#include "tests/coverage_cases.h"

namespace rast {
namespace {

using reference::ExactGeometry;
using reference::GridTriangle;
using reference::SampleRule;
using reference::WindowPoint;
using reference::WindowTriangle;
using test_support::randomTriangle;
using test_support::TriangleHashShader;

TEST(ExactRasterizer, SnapsToNearestTiesToEven) {
  const FixedPointFormat f4 = FixedPointFormat::d24_4();
  EXPECT_EQ(reference::snapExactly(0.5 / 16, f4), 0);
  EXPECT_EQ(reference::snapExactly(1.5 / 16, f4), 2);
  EXPECT_EQ(reference::snapExactly(2.5 / 16, f4), 2);
  EXPECT_EQ(reference::snapExactly(-0.5 / 16, f4), 0);
  EXPECT_EQ(reference::snapExactly(-1.5 / 16, f4), -2);
  EXPECT_EQ(reference::snapExactly(0.50001 / 16, f4), 1);
  EXPECT_EQ(reference::snapExactly(1e30, f4), f4.guardBandSubpixels());
  EXPECT_EQ(reference::snapExactly(-1e30, f4), -f4.guardBandSubpixels());
  // The pipeline's snapping (std::nearbyint) is the same function.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-5000.0, 5000.0);
  for (int bits = 1; bits <= 8; ++bits) {
    const FixedPointFormat f = FixedPointFormat::withFractionBits(bits);
    for (int i = 0; i < 20000; ++i) {
      // Half of them exactly on a tie.
      const double v = i % 2 ? u(rng) : (std::floor(u(rng)) + 0.5) / f.subpixelsPerPixel();
      ASSERT_EQ(reference::snapExactly(v, f), snapToSubpixels(v, f)) << v << " at " << bits;
    }
  }
}

// A square split along its diagonal, corners on pixel centres: every sample of the square's
// edges and diagonal is a tie, and each is owned by exactly one triangle or none.
TEST(ExactRasterizer, TopLeftRuleOnASplitSquare) {
  const WindowTriangle upper = {{{2.5, 2.5}, {6.5, 2.5}, {6.5, 6.5}}};
  const WindowTriangle lower = {{{2.5, 2.5}, {6.5, 6.5}, {2.5, 6.5}}};
  const std::vector<WindowTriangle> both = {upper, lower};
  const ExactGeometry g{true, FixedPointFormat::d24_4(), SampleRule::TopLeft};
  const reference::CoverageCounts c = reference::rasterizeCounts(both, 10, 10, g);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      // The top and left sides belong to the square, the bottom and right sides do not.
      const uint32_t expected = x >= 2 && x < 6 && y >= 2 && y < 6;
      EXPECT_EQ(c.counts[size_t(y) * 10 + x], expected) << x << ", " << y;
    }
  const reference::CoverageCounts closed =
      reference::rasterizeCounts(both, 10, 10, {true, FixedPointFormat::d24_4(), SampleRule::ClosedTriangle});
  uint32_t twice = 0, total = 0;
  for (uint32_t n : closed.counts) twice += n == 2, total += n;
  EXPECT_EQ(twice, 5u);       // the diagonal, corners included
  EXPECT_EQ(total, 25u + 5u);  // the closed 5x5 samples, the diagonal counted twice
}

TEST(ExactRasterizer, ExactGeometryRefusesWhatItCannotRepresent) {
  const ExactGeometry exact{false, {}, SampleRule::TopLeft};
  GridTriangle g;
  EXPECT_TRUE(reference::toGrid({{{0.1f, 0.2f}, {300.3f, 0.7f}, {5.25f, 200.0f}}}, exact, g));
  EXPECT_EQ(g.fractionBits, 27);  // 0.1f = 13421773 / 2^27
  EXPECT_FALSE(reference::toGrid({{{1e-30, 0.0}, {600.0, 0.0}, {0.0, 300.0}}}, exact, g));
  EXPECT_FALSE(reference::toGrid({{{NAN, 0.0}, {6.0, 0.0}, {0.0, 3.0}}}, exact, g));
  // The exact geometry is the given triangle itself; snapping at 16.8 moves an edge 2^-20 pixel
  // from a sample onto it, where the fill rule decides.
  const WindowTriangle inside = {{{0.5 - 0x1p-20, 0.0}, {8.0, 0.0}, {0.5 - 0x1p-20, 8.0}}};
  ASSERT_TRUE(reference::toGrid(inside, exact, g));
  EXPECT_TRUE(reference::coversPixelCentre(g, 0, 0, SampleRule::TopLeft));
  const WindowTriangle left = {{{0.5 + 0x1p-20, 0.0}, {8.0, 0.0}, {0.5 + 0x1p-20, 8.0}}};
  ASSERT_TRUE(reference::toGrid(left, exact, g));
  EXPECT_FALSE(reference::coversPixelCentre(g, 0, 0, SampleRule::TopLeft));
  ASSERT_TRUE(reference::toGrid(left, {true, FixedPointFormat::d16_8(), SampleRule::TopLeft}, g));
  EXPECT_TRUE(reference::coversPixelCentre(g, 0, 0, SampleRule::TopLeft));  // on a left edge
  const WindowTriangle right = {{{0.5 - 0x1p-20, 0.0}, {0.5 - 0x1p-20, 8.0}, {-8.0, 0.0}}};
  ASSERT_TRUE(reference::toGrid(right, exact, g));
  EXPECT_FALSE(reference::coversPixelCentre(g, 0, 0, SampleRule::TopLeft));
  ASSERT_TRUE(reference::toGrid(right, {true, FixedPointFormat::d16_8(), SampleRule::TopLeft}, g));
  EXPECT_FALSE(reference::coversPixelCentre(g, 0, 0, SampleRule::TopLeft));  // on a right edge
  EXPECT_TRUE(reference::coversPixelCentre(g, 0, 0, SampleRule::ClosedTriangle));
}

// ---------------------------------------------------------------------------------------------
// The pipeline against the reference.

class ExactCoverage : public ::testing::TestWithParam<int> {};

TEST_P(ExactCoverage, PipelineEqualsReferenceBitForBit) {
  const int bits = GetParam();
  const FixedPointFormat format = FixedPointFormat::withFractionBits(bits);
  const uint64_t seed = 0xe4ac7000 + bits;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  constexpr int W = 88, H = 72, kBatches = 6, kPerBatch = 300;
  uint64_t covered = 0, ties = 0;
  for (int batch = 0; batch < kBatches; ++batch) {
    std::vector<WindowTriangle> triangles;
    for (int i = 0; i < kPerBatch; ++i) triangles.push_back(randomTriangle(rng, format, W, H));
    const test_support::DrawnCoverage drawn =
        test_support::drawWindowTriangles(triangles, W, H, format, RasterMode::FixedPoint);
    ASSERT_TRUE(drawn.status.isOk()) << drawn.status.message();

    std::vector<uint32_t> counts(size_t(W) * H, 0), closedCounts(size_t(W) * H, 0);
    std::vector<uint64_t> expectedHashes(size_t(W) * H, 0);
    for (size_t i = 0; i < triangles.size(); ++i) {
      GridTriangle g;
      ASSERT_TRUE(reference::toGrid(triangles[i], {true, format, SampleRule::TopLeft}, g));
      reference::forEachCoveredPixel(g, {0, 0, W, H}, SampleRule::TopLeft, [&](int x, int y) {
        ++counts[size_t(y) * W + x];
        expectedHashes[size_t(y) * W + x] += TriangleHashShader::hashTriangle(i);
      });
      reference::forEachCoveredPixel(g, {0, 0, W, H}, SampleRule::ClosedTriangle,
                                     [&](int x, int y) { ++closedCounts[size_t(y) * W + x]; });
    }
    int wrong = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const size_t i = size_t(y) * W + x;
        covered += counts[i];
        ties += closedCounts[i] - counts[i];
        if ((drawn.counts[i] != counts[i] || drawn.hashes[i] != expectedHashes[i]) && ++wrong <= 5)
          ADD_FAILURE() << format.name() << " batch " << batch << ": pixel (" << x << ", " << y
                        << ") count " << drawn.counts[i] << ", reference " << counts[i];
      }
    ASSERT_EQ(wrong, 0) << format.name() << " batch " << batch;
  }
  // Not vacuous: many samples covered, and many decided by the fill rule alone (on an edge).
  EXPECT_GT(covered, 100000u) << format.name();
  EXPECT_GT(ties, 500u) << format.name();
  std::cout << format.name() << ": " << covered << " covered samples, " << ties
            << " of the closed triangles' samples excluded by the fill rule\n";
}

INSTANTIATE_TEST_SUITE_P(EveryPrecision, ExactCoverage, ::testing::Range(1, 9),
                         [](const auto& info) { return "bits" + std::to_string(info.param); });

}  // namespace
}  // namespace rast
