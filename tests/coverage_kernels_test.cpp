// Every SIMD coverage kernel against the scalar int64 reference, bit for bit.
#include <gtest/gtest.h>

#include <random>

#include "rasterizer/coverage_kernels.h"
#include "rasterizer/triangle_setup.h"

namespace rast {
namespace {


class CoverageKernelTest : public ::testing::TestWithParam<std::string> {};

// A tile that an edge of the triangle crosses, so the test exercises partial masks rather than
// the trivially inside or outside tiles that dominate large triangles.
void tileOnEdge(const std::array<SnappedPoint, 3>& v, std::mt19937_64& rng, FixedPointFormat f,
                int& tileX, int& tileY) {
  const int e = int(rng() % 3);
  const double t = std::uniform_real_distribution<double>(0, 1)(rng);
  const double x = v[e].x + t * (double(v[(e + 1) % 3].x) - v[e].x);
  const double y = v[e].y + t * (double(v[(e + 1) % 3].y) - v[e].y);
  tileX = int(std::floor(std::ldexp(x, -f.fractionBits) / kTileSize));
  tileY = int(std::floor(std::ldexp(y, -f.fractionBits) / kTileSize));
}

// One million triangles per kernel and precision: small ones around a few tiles (all on the
// subpixel grid, many with vertices exactly on sample positions so ties occur), medium ones, and
// ones spanning the whole guard band (which take the int64 path where 32-bit lanes would not be
// exact).
TEST_P(CoverageKernelTest, MatchesScalarReferenceOnRandomTriangles) {
  CoverageKernel kernel;
  ASSERT_TRUE(findCoverageKernel(GetParam(), kernel));
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    const uint64_t seed = 0xC0FFEE + uint64_t(format.fractionBits);
    SCOPED_TRACE("format " + format.name() + ", seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const int32_t guard = format.guardBandSubpixels();
    const PixelRect everywhere{-(1 << 30), -(1 << 30), 1 << 30, 1 << 30};
    const int32_t one = format.subpixelsPerPixel();
    int mismatches = 0, partialTiles = 0;
    for (int i = 0; i < 500000 && mismatches < 5; ++i) {
      const int sizeClass = i % 4;
      const int32_t extent = sizeClass == 0 ? 3 * kTileSize * one
                             : sizeClass == 1 ? 64 * kTileSize * one
                             : sizeClass == 2 ? 4096 * one
                                              : guard;
      std::uniform_int_distribution<int32_t> coord(-extent, extent);
      std::array<SnappedPoint, 3> v;
      for (SnappedPoint& p : v) {
        p = {coord(rng), coord(rng)};
        // A quarter of the small triangles have vertices at pixel centres: samples on edges.
        if (sizeClass == 0 && rng() % 4 == 0) {
          p.x = (p.x & ~(one - 1)) | (one / 2);
          p.y = (p.y & ~(one - 1)) | (one / 2);
        }
      }
      CoverageSetup setup;
      if (setupCoverage(v, everywhere, format, setup) != SetupOutcome::Accepted) continue;
      int tx, ty;
      tileOnEdge(v, rng, format, tx, ty);
      for (int k = 0; k < 2; ++k) {  // the tile on the edge and a neighbour
        const int x = tx + k * int(rng() % 3) - k, y = ty + k * int(rng() % 3) - k;
        const CoverageMask expected = coverageScalar(setup.edges, setup.bounds, x, y, format);
        const TileCoverageResult actual = coverTile(kernel, setup.edges, setup.bounds, x, y, format);
        // The whole-tile decision must agree with the corner classification, too.
        EXPECT_EQ(actual.kind, classifyTile(setup.edges, setup.bounds, x, y, format));
        partialTiles += expected != 0 && expected != kFullMask;
        if (actual.mask != expected) {
          ++mismatches;
          ADD_FAILURE() << "triangle " << i << " (" << v[0].x << "," << v[0].y << ") (" << v[1].x
                        << "," << v[1].y << ") (" << v[2].x << "," << v[2].y << ") tile " << x
                        << "," << y << ": expected " << std::hex << expected << " got " << actual.mask;
        }
      }
    }
    // Guards against a generator that stopped producing the hard (partial) cases.
    EXPECT_GT(partialTiles, 200000);
  }
}

// Bounds smaller than the tile (viewport and scissor edges) mask the kernel's result.
TEST_P(CoverageKernelTest, RespectsBoundsInsideTheTile) {
  CoverageKernel kernel;
  ASSERT_TRUE(findCoverageKernel(GetParam(), kernel));
  const FixedPointFormat f = FixedPointFormat::d24_4();
  const std::array<SnappedPoint, 3> v = {{{-1000, -1000}, {4000, -1000}, {-1000, 4000}}};
  CoverageSetup setup;
  const PixelRect clip{2, 3, 6, 5};
  ASSERT_EQ(setupCoverage(v, clip, f, setup), SetupOutcome::Accepted);
  EXPECT_EQ(coverTile(kernel, setup.edges, setup.bounds, 0, 0, f).mask, rectMask(clip, 0, 0));
  EXPECT_EQ(coverTile(kernel, setup.edges, setup.bounds, 1, 0, f).mask, 0u);
}

std::vector<std::string> kernelNames() {
  std::vector<std::string> names;
  for (const CoverageKernel& k : availableCoverageKernels()) names.push_back(k.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllTargets, CoverageKernelTest, ::testing::ValuesIn(kernelNames()),
                         [](const auto& info) { return info.param; });

TEST(CoverageKernels, ListStartsWithScalarAndResolvesAuto) {
  const std::vector<CoverageKernel> kernels = availableCoverageKernels();
  ASSERT_FALSE(kernels.empty());
  EXPECT_EQ(kernels.front().name, "scalar");
  EXPECT_EQ(kernels.front().simd, nullptr);
  CoverageKernel best;
  ASSERT_TRUE(findCoverageKernel("AUTO", best));
  EXPECT_EQ(best.name, kernels.back().name);
  CoverageKernel none;
  EXPECT_FALSE(findCoverageKernel("no-such-target", none));
}

}  // namespace
}  // namespace rast
