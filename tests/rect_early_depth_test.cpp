// The fused raster and early-depth kernel of every SIMD target against the reference, bit for
// bit: coverageScalar's mask, interpolateDepth at each covered pixel, depthPasses, and the depths
// written.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <random>

#include "pipeline/interpolate.h"
#include "pipeline/merge.h"
#include "pipeline/rect_early_depth.h"
#include "rasterizer/triangle_setup.h"

namespace rast {
namespace {

bool passes(CompareOp op, float z, float stored) {
  using enum CompareOp;
  switch (op) {
    case Never: return depthPasses<Never>(z, stored);
    case Less: return depthPasses<Less>(z, stored);
    case Equal: return depthPasses<Equal>(z, stored);
    case LessEqual: return depthPasses<LessEqual>(z, stored);
    case Greater: return depthPasses<Greater>(z, stored);
    case NotEqual: return depthPasses<NotEqual>(z, stored);
    case GreaterEqual: return depthPasses<GreaterEqual>(z, stored);
    case Always: return depthPasses<Always>(z, stored);
  }
  return false;
}

// A depth plane: mostly the planes of real scenes (values in [0, 1], gentle slopes), sometimes
// ones that leave [0, 1] over the tile (the clamp), and a few that are infinite or NaN.
PlaneEquation randomPlane(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f), slope(-0.02f, 0.02f);
  switch (rng() % 10) {
    case 0: return {u(rng) * 3 - 1, slope(rng) * 50, slope(rng) * 50};
    case 1: return {std::numeric_limits<float>::quiet_NaN(), slope(rng), slope(rng)};
    case 2: return {u(rng), std::numeric_limits<float>::infinity(), slope(rng)};
    case 3: return {-0.0f, 0.0f, 0.0f};
    default: return {u(rng), slope(rng), slope(rng)};
  }
}

class RectEarlyDepthTest : public ::testing::TestWithParam<std::string> {};

// Random triangles of three sizes: a few pixels (around one tile), medium, and long-edged ones
// (to half the guard band, beyond the 32-bit lanes' limit) whose bounds a scissor cuts to a few
// tiles. For each, one tile
// its bounds meet, random stored depths (some equal to the triangle's, so that ties occur; some
// NaN and -0), every compare op, with and without the depth write.
TEST_P(RectEarlyDepthTest, MatchesReferenceOnRandomTriangles) {
  CoverageKernel kernel;
  ASSERT_TRUE(findCoverageKernel(GetParam(), kernel));
  const RectEarlyDepthFn fused = rectEarlyDepthFor(kernel);
  if (!kernel.simd) {
    EXPECT_EQ(fused, nullptr);  // the scalar reference keeps the general path
    return;
  }
  ASSERT_NE(fused, nullptr);
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    const uint64_t seed = 0x5EED0 + uint64_t(format.fractionBits);
    SCOPED_TRACE("format " + format.name() + ", seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const int32_t one = format.subpixelsPerPixel();
    // The kernel's 32-bit lanes take edges with |a|, |b| < 2^(26-F) (rect_early_depth.cpp).
    const int64_t laneLimit = int64_t{1} << (26 - format.fractionBits);
    int mismatches = 0, longEdged = 0, partial = 0, passedSome = 0, failedSome = 0;
    for (int i = 0; i < 200000 && mismatches < 5; ++i) {
      const int sizeClass = i % 3;
      const int32_t guard = format.guardBandSubpixels();
      const int32_t extent = sizeClass == 0   ? 3 * kTileSize * one
                             : sizeClass == 1 ? 40 * kTileSize * one
                                              : guard / 2;
      // Around a random tile of a 4096-pixel screen, so that tiles far from the origin occur.
      const int32_t cx = int32_t(rng() % 4096) * one, cy = int32_t(rng() % 4096) * one;
      std::uniform_int_distribution<int32_t> coord(-extent, extent);
      std::array<SnappedPoint, 3> v;
      for (SnappedPoint& p : v) {
        p = {std::clamp(cx + coord(rng), -guard, guard), std::clamp(cy + coord(rng), -guard, guard)};
        if (rng() % 4 == 0) {  // on a pixel centre: samples exactly on edges
          p.x = (p.x & ~(one - 1)) | (one / 2);
          p.y = (p.y & ~(one - 1)) | (one / 2);
        }
      }
      // Long-edged triangles through a scissor of up to 3x3 tiles near their centre.
      PixelRect clip{-(1 << 20), -(1 << 20), 1 << 20, 1 << 20};
      if (sizeClass == 2) {
        const int px = cx / one + int(rng() % 16) - 8, py = cy / one + int(rng() % 16) - 8;
        clip = {px, py, px + 1 + int(rng() % 24), py + 1 + int(rng() % 24)};
      }
      CoverageSetup setup;
      if (setupCoverage(v, clip, format, setup) != SetupOutcome::Accepted) continue;
      SetupTriangle<0> t;
      t.edges = setup.edges;
      t.bounds = TriangleBounds(setup.bounds.intersect({0, 0, 32768, 32768}));
      const PixelRect b = t.bounds;
      if (b.empty()) continue;
      t.depth = randomPlane(rng);
      const int tileX = (b.x0 + int(rng() % uint32_t(b.x1 - b.x0))) / kTileSize;
      const int tileY = (b.y0 + int(rng() % uint32_t(b.y1 - b.y0))) / kTileSize;
      bool wide = false;
      for (const EdgeFunction& e : t.edges)
        wide |= std::abs(int64_t{e.a}) >= laneLimit || std::abs(int64_t{e.b}) >= laneLimit;
      longEdged += wide;

      // The reference: each pixel of the tile within the bounds and inside the triangle, its
      // depth as the back end interpolates it.
      const CoverageMask covered = coverageScalar(t.edges, b, tileX, tileY, format);
      std::array<float, kTileSize * kTileSize> z{}, stored{};
      for (int k = 0; k < kTileSize * kTileSize; ++k) {
        z[size_t(k)] = interpolateDepth(t, float(tileX * kTileSize + k % kTileSize - b.x0),
                                        float(tileY * kTileSize + k / kTileSize - b.y0));
        switch (rng() % 8) {
          case 0: stored[size_t(k)] = z[size_t(k)]; break;  // ties
          case 1: stored[size_t(k)] = std::numeric_limits<float>::quiet_NaN(); break;
          case 2: stored[size_t(k)] = (rng() % 2) ? -0.0f : 0.0f; break;
          case 3: stored[size_t(k)] = 1.0f; break;
          default: stored[size_t(k)] = std::uniform_real_distribution<float>(0, 1)(rng);
        }
      }
      const CompareOp op = CompareOp(rng() % 8);
      const bool write = rng() % 4 != 0;
      CoverageMask passed = 0;
      std::array<float, kTileSize * kTileSize> expected = stored;
      for (int k = 0; k < kTileSize * kTileSize; ++k)
        if ((covered >> k & 1) && passes(op, z[size_t(k)], stored[size_t(k)])) {
          passed |= CoverageMask{1} << k;
          if (write) expected[size_t(k)] = z[size_t(k)];
        }
      partial += covered != 0 && covered != kFullMask;
      passedSome += passed != 0;
      failedSome += passed != covered;

      std::array<float, kTileSize * kTileSize> actual = stored;
      const RectEarlyDepth r = fused(t, tileX, tileY, {format, op, write}, actual.data());
      bool same = r.covered == covered && r.passed == passed;
      for (size_t k = 0; k < actual.size(); ++k)
        same &= std::bit_cast<uint32_t>(actual[k]) == std::bit_cast<uint32_t>(expected[k]);
      if (!same) {
        ++mismatches;
        ADD_FAILURE() << "triangle " << i << " (" << v[0].x << "," << v[0].y << ") (" << v[1].x
                      << "," << v[1].y << ") (" << v[2].x << "," << v[2].y << ") tile " << tileX
                      << "," << tileY << " op " << int(op) << " write " << write << std::hex
                      << ": covered " << r.covered << " expected " << covered << ", passed "
                      << r.passed << " expected " << passed;
      }
    }
    // Guards against a generator that stopped producing the cases that matter: both edge paths,
    // partial masks, and depth tests that pass and fail.
    EXPECT_GT(longEdged, 20000);
    EXPECT_GT(partial, 50000);
    EXPECT_GT(passedSome, 50000);
    EXPECT_GT(failedSome, 50000);
  }
}

std::vector<std::string> kernelNames() {
  std::vector<std::string> names;
  for (const CoverageKernel& k : availableCoverageKernels()) names.push_back(k.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllTargets, RectEarlyDepthTest, ::testing::ValuesIn(kernelNames()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace rast
