// The top-left fill rule on hand-built triangles: samples exactly on left, right, top and bottom
// edges, on vertices, and on edges shared by two triangles. Coordinates are window pixels, y down,
// pixel centres at +0.5, so an edge through x = k + 0.5 passes exactly through samples.
#include "rasterizer/edge_function.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/draw.h"
#include "rasterizer/coverage.h"
#include "rasterizer/fixed_point.h"
#include "rasterizer/triangle_setup.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

struct Pt {
  double x, y;  // pixels
};
using Tri = std::array<Pt, 3>;

const FixedPointFormat kFormats[] = {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()};
const PixelRect kWideClip{-1000, -1000, 1000, 1000};

// Coverage of tile (0, 0), the pixels [0, 8) x [0, 8), for the vertices in the given order.
CoverageMask tileCoverageInOrder(const Tri& t, FixedPointFormat f) {
  std::array<SnappedPoint, 3> v;
  for (int i = 0; i < 3; ++i) v[i] = {snapToSubpixels(t[i].x, f), snapToSubpixels(t[i].y, f)};
  CoverageSetup setup;
  if (setupCoverage(v, kWideClip, f, setup) != SetupOutcome::Accepted) return 0;
  return coverageScalar(setup.edges, setup.bounds, 0, 0, f);
}

// Coverage of tile (0, 0); checks that all six vertex orders (both windings, every starting
// vertex) give the same mask, since the fill rule is a property of the triangle, not of its order.
CoverageMask tileCoverage(Tri t, FixedPointFormat f) {
  const CoverageMask first = tileCoverageInOrder(t, f);
  std::array<int, 3> order{0, 1, 2};
  while (std::next_permutation(order.begin(), order.end())) {
    const Tri p{t[order[0]], t[order[1]], t[order[2]]};
    EXPECT_EQ(tileCoverageInOrder(p, f), first)
        << "order " << order[0] << order[1] << order[2] << " changes the coverage";
  }
  return first;
}

template <class Pred>
CoverageMask maskWhere(Pred pred) {
  CoverageMask m = 0;
  for (int y = 0; y < kTileSize; ++y)
    for (int x = 0; x < kTileSize; ++x)
      if (pred(x, y)) m |= CoverageMask{1} << coverageBit(x, y);
  return m;
}

bool covers(CoverageMask m, int x, int y) { return (m >> coverageBit(x, y)) & 1; }

// ---- The edge function itself ------------------------------------------------------------------

TEST(EdgeFunction, CoefficientsAndTopLeftClassification) {
  // An edge is top-left exactly when the interior is to its +x side (a > 0), or it is horizontal
  // with the interior below it (a == 0, b > 0); for every other edge c carries the -1 bias.
  struct Case {
    SnappedPoint from, to;
    int64_t a, b;
    bool topLeft;
  };
  const Case cases[] = {
      {{0, 16}, {0, 0}, 16, 0, true},    // upwards: interior at +x, a left edge
      {{0, 0}, {0, 16}, -16, 0, false},  // downwards: interior at -x, a right edge
      {{0, 0}, {16, 0}, 0, 16, true},    // rightwards: interior below, a top edge
      {{16, 0}, {0, 0}, 0, -16, false},  // leftwards: interior above, a bottom edge
      {{0, 16}, {16, 0}, 16, 16, true},  // up and right: interior at +x
      {{16, 0}, {0, 16}, -16, -16, false},
      {{0, 0}, {16, 16}, -16, 16, false},  // down and right: interior at -x
      {{16, 16}, {0, 0}, 16, -16, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message()
                 << "(" << c.from.x << "," << c.from.y << ")->(" << c.to.x << "," << c.to.y << ")");
    const EdgeFunction e = EdgeFunction::through(c.from, c.to);
    EXPECT_EQ(e.a, c.a);
    EXPECT_EQ(e.b, c.b);
    EXPECT_EQ(EdgeFunction::isTopLeft(e.a, e.b), c.topLeft);
    // On the edge E is exactly the bias: 0 for top-left edges (covered), -1 otherwise (not).
    const int64_t onEdge = c.topLeft ? 0 : -1;
    EXPECT_EQ(e.at(c.from.x, c.from.y), onEdge);
    EXPECT_EQ(e.at(c.to.x, c.to.y), onEdge);
    EXPECT_EQ(e.at((c.from.x + c.to.x) / 2, (c.from.y + c.to.y) / 2), onEdge);
  }
}

// ---- A sample exactly on one edge ---------------------------------------------------------------
// Each triangle below has its other two edges hundreds of pixels from tile (0, 0), so inside the
// tile the coverage is one closed or open half-plane: the expected masks are exact.

TEST(EdgeFunction, TopLeftRuleIncludesLeftEdge) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Vertical edge x = 2.5 with the interior to the right: a left edge, so column 2 is covered.
    const CoverageMask m = tileCoverage({Pt{2.5, -300}, Pt{2.5, 300}, Pt{500, 0}}, f);
    EXPECT_EQ(m, maskWhere([](int x, int) { return x >= 2; }));
  }
}

TEST(EdgeFunction, TopLeftRuleExcludesRightEdge) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Vertical edge x = 5.5 with the interior to the left: a right edge, so column 5 is not.
    const CoverageMask m = tileCoverage({Pt{5.5, -300}, Pt{5.5, 300}, Pt{-500, 0}}, f);
    EXPECT_EQ(m, maskWhere([](int x, int) { return x <= 4; }));
  }
}

TEST(EdgeFunction, TopLeftRuleIncludesTopEdge) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Horizontal edge y = 2.5 with the interior below (y down): a top edge, so row 2 is covered.
    const CoverageMask m = tileCoverage({Pt{-300, 2.5}, Pt{300, 2.5}, Pt{0, 500}}, f);
    EXPECT_EQ(m, maskWhere([](int, int y) { return y >= 2; }));
  }
}

TEST(EdgeFunction, TopLeftRuleExcludesBottomEdge) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Horizontal edge y = 5.5 with the interior above: a bottom edge, so row 5 is not covered.
    const CoverageMask m = tileCoverage({Pt{-300, 5.5}, Pt{300, 5.5}, Pt{0, -500}}, f);
    EXPECT_EQ(m, maskWhere([](int, int y) { return y <= 4; }));
  }
}

TEST(EdgeFunction, TopLeftRuleOnDiagonalEdges) {
  // A sloped edge is never a top edge; whether its samples count depends only on which side
  // (in x) the interior lies, so a left edge keeps them and a right edge drops them.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // The line x = y passes through the samples (k + .5, k + .5).
    EXPECT_EQ(tileCoverage({Pt{-300, -300}, Pt{300, 300}, Pt{600, -300}}, f),
              maskWhere([](int x, int y) { return x >= y; }));  // interior at +x: left edge
    EXPECT_EQ(tileCoverage({Pt{-300, -300}, Pt{300, 300}, Pt{-600, 300}}, f),
              maskWhere([](int x, int y) { return x < y; }));  // interior at -x: right edge
    // The line x + y = 8 passes through the samples with x + y = 7.
    EXPECT_EQ(tileCoverage({Pt{-292, 300}, Pt{308, -300}, Pt{600, 300}}, f),
              maskWhere([](int x, int y) { return x + y >= 7; }));  // interior at +x: left edge
    EXPECT_EQ(tileCoverage({Pt{-292, 300}, Pt{308, -300}, Pt{-600, -300}}, f),
              maskWhere([](int x, int y) { return x + y < 7; }));  // interior at -x: right edge
    // A shallow line, 2y = x + 0.5 (through (k*2 + .5, k + .5)): interior below it lies at -x.
    EXPECT_EQ(tileCoverage({Pt{-299.5, -149.5}, Pt{300.5, 150.5}, Pt{-300, 600}}, f),
              maskWhere([](int x, int y) { return 2 * y + 1 > x + 1; }));
    EXPECT_EQ(tileCoverage({Pt{-299.5, -149.5}, Pt{300.5, 150.5}, Pt{300, -600}}, f),
              maskWhere([](int x, int y) { return 2 * y + 1 <= x + 1; }));
  }
}

TEST(EdgeFunction, HalfPlaneJustOffTheSampleIgnoresTheRule) {
  // One subpixel away from the samples there is no tie: the same edges as above, moved by one
  // subpixel, cover or miss the column whatever kind of edge they are.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    const double d = std::ldexp(1.0, -f.fractionBits);
    // Right edge at x = 5.5 + d: column 5 now strictly inside.
    EXPECT_EQ(tileCoverage({Pt{5.5 + d, -300}, Pt{5.5 + d, 300}, Pt{-500, 0}}, f),
              maskWhere([](int x, int) { return x <= 5; }));
    // Left edge at x = 2.5 + d: column 2 now strictly outside.
    EXPECT_EQ(tileCoverage({Pt{2.5 + d, -300}, Pt{2.5 + d, 300}, Pt{500, 0}}, f),
              maskWhere([](int x, int) { return x >= 3; }));
    // Bottom edge at y = 5.5 + d: row 5 strictly inside; top edge at y = 2.5 + d: row 2 outside.
    EXPECT_EQ(tileCoverage({Pt{-300, 5.5 + d}, Pt{300, 5.5 + d}, Pt{0, -500}}, f),
              maskWhere([](int, int y) { return y <= 5; }));
    EXPECT_EQ(tileCoverage({Pt{-300, 2.5 + d}, Pt{300, 2.5 + d}, Pt{0, 500}}, f),
              maskWhere([](int, int y) { return y >= 3; }));
  }
}

// ---- Samples on vertices ------------------------------------------------------------------------

TEST(EdgeFunction, SamplesOnVerticesFollowBothEdges) {
  // A vertex sample is covered only when both edges meeting there keep it.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Top-left corner (2.5, 2.5): on the left edge and the top edge, so covered. (6.5, 2.5): on
    // the top edge but also on the hypotenuse, a right edge, so not; likewise (2.5, 6.5).
    const CoverageMask upper = tileCoverage({Pt{2.5, 2.5}, Pt{6.5, 2.5}, Pt{2.5, 6.5}}, f);
    EXPECT_EQ(upper, maskWhere([](int x, int y) { return x >= 2 && y >= 2 && x + y <= 7; }));
    EXPECT_TRUE(covers(upper, 2, 2));
    EXPECT_FALSE(covers(upper, 6, 2));
    EXPECT_FALSE(covers(upper, 2, 6));
    EXPECT_EQ(std::popcount(upper), 10);
    // The other half of the square: the hypotenuse is its left edge (kept), (6.5, 6.5) lies on
    // a right and a bottom edge (dropped), and (6.5, 2.5) / (2.5, 6.5) on a right / bottom edge.
    const CoverageMask lower = tileCoverage({Pt{6.5, 6.5}, Pt{2.5, 6.5}, Pt{6.5, 2.5}}, f);
    EXPECT_EQ(lower, maskWhere([](int x, int y) { return x <= 5 && y <= 5 && x + y >= 8; }));
    EXPECT_FALSE(covers(lower, 6, 6));
    EXPECT_EQ(std::popcount(lower), 6);
    // Together: the square [2.5, 6.5]^2 without its right column and bottom row, each sample once.
    EXPECT_EQ(upper & lower, 0u);
    EXPECT_EQ(upper | lower,
              maskWhere([](int x, int y) { return x >= 2 && x <= 5 && y >= 2 && y <= 5; }));
  }
}

TEST(EdgeFunction, SingleSampleTriangles) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // A triangle whose only sample is its top-left vertex: covered exactly there.
    EXPECT_EQ(tileCoverage({Pt{3.5, 4.5}, Pt{4.25, 4.5}, Pt{3.5, 5.25}}, f),
              CoverageMask{1} << coverageBit(3, 4));
    // The same shape turned so the sample is its bottom-right vertex: not covered at all.
    EXPECT_EQ(tileCoverage({Pt{3.5, 4.5}, Pt{2.75, 4.5}, Pt{3.5, 3.75}}, f), 0u);
    // A sample strictly inside a small triangle.
    EXPECT_EQ(tileCoverage({Pt{3.25, 4.25}, Pt{4.0, 4.25}, Pt{3.25, 5.0}}, f),
              CoverageMask{1} << coverageBit(3, 4));
  }
}

// ---- Shared edges
// --------------------------------------------------------------------------------

// Two triangles on either side of the edge p-q. The apexes are far from the tile, so together they
// cover the whole tile; the fill rule must give every sample to exactly one of them.
void expectSharedEdgePartitionsTile(Pt p, Pt q, Pt apexA, Pt apexB, CoverageMask expectedA,
                                    FixedPointFormat f) {
  const CoverageMask a = tileCoverage({p, q, apexA}, f);
  const CoverageMask b = tileCoverage({q, p, apexB}, f);
  EXPECT_EQ(a & b, 0u) << "samples covered twice";
  EXPECT_EQ(a | b, kFullMask) << "samples covered by neither";
  EXPECT_EQ(a, expectedA);
}

TEST(EdgeFunction, SharedHorizontalEdgeCoversEachSampleOnce) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Row 4 lies on y = 4.5: the lower triangle sees it as a top edge and takes it.
    expectSharedEdgePartitionsTile({-300, 4.5}, {300, 4.5}, {0, 600}, {0, -600},
                                   maskWhere([](int, int y) { return y >= 4; }), f);
  }
}

TEST(EdgeFunction, SharedVerticalEdgeCoversEachSampleOnce) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Column 3 lies on x = 3.5: the right triangle sees it as a left edge and takes it.
    expectSharedEdgePartitionsTile({3.5, -300}, {3.5, 300}, {600, 0}, {-600, 0},
                                   maskWhere([](int x, int) { return x >= 3; }), f);
  }
}

TEST(EdgeFunction, SharedDiagonalEdgeCoversEachSampleOnce) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // x = y through the diagonal samples: the triangle on the +x side takes them.
    expectSharedEdgePartitionsTile({-300, -300}, {300, 300}, {600, -600}, {-600, 600},
                                   maskWhere([](int x, int y) { return x >= y; }), f);
    // x + y = 8 through the anti-diagonal samples x + y = 7: again the +x side takes them.
    expectSharedEdgePartitionsTile({-292, 300}, {308, -300}, {600, 600}, {-600, -600},
                                   maskWhere([](int x, int y) { return x + y >= 7; }), f);
    // A steep edge, 3x - y = 6, through the samples with 3 * px - py = 5 ((2, 1), (3, 4), ...).
    expectSharedEdgePartitionsTile({-98, -300}, {102, 300}, {600, -600}, {-600, 600},
                                   maskWhere([](int x, int y) { return 3 * x - y >= 5; }), f);
  }
}

TEST(EdgeFunction, SharedEdgeEndingAtASampleCoversItOnce) {
  // The shared edge ends exactly on sample (4, 4), a vertex of both triangles, and a third
  // triangle closes the fan below; the vertex must still be covered by exactly one of the three.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    const Pt c{4.5, 4.5};
    const CoverageMask a = tileCoverage({c, {4.5, -300}, {300, 300}}, f);
    const CoverageMask b = tileCoverage({c, {300, 300}, {-300, 300}}, f);
    const CoverageMask d = tileCoverage({c, {-300, 300}, {4.5, -300}}, f);
    EXPECT_EQ(a & b, 0u);
    EXPECT_EQ(b & d, 0u);
    EXPECT_EQ(a & d, 0u);
    EXPECT_EQ(a | b | d, kFullMask);
    // At c, `a` has the vertical edge above c (interior at +x) and the diagonal y = x (interior
    // at +x too): both left edges, so `a` alone takes c. `b` has c on its bottom-left edge
    // diagonal (interior at -x: a right edge) and `d` on its vertical edge (interior at -x).
    EXPECT_TRUE(covers(a, 4, 4));
  }
}

TEST(EdgeFunction, FanAroundAPixelCentreCoversEachSampleOnce) {
  // Eight triangles around the sample (4.5, 4.5), with edges leaving it horizontally, vertically
  // and diagonally, all through samples. The ring is the square [0.5, 8.5]^2, whose left and top
  // sides are left and top edges, so each of the 64 samples of the tile belongs to exactly one.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    const Pt c{4.5, 4.5};
    const Pt ring[8] = {{0.5, 0.5}, {4.5, 0.5}, {8.5, 0.5}, {8.5, 4.5},
                        {8.5, 8.5}, {4.5, 8.5}, {0.5, 8.5}, {0.5, 4.5}};
    std::array<int, 64> count{};
    for (int i = 0; i < 8; ++i) {
      const CoverageMask m = tileCoverage({c, ring[i], ring[(i + 1) % 8]}, f);
      for (int bit = 0; bit < 64; ++bit) count[bit] += int((m >> bit) & 1);
    }
    for (int bit = 0; bit < 64; ++bit)
      EXPECT_EQ(count[bit], 1) << "sample (" << bit % 8 << ", " << bit / 8 << ")";
  }
}

TEST(EdgeFunction, PipelineFanWritesEveryPixelOnce) {
  // The same fan through the whole pipeline in window space: with depth testing off, the
  // fragment count per pixel exposes any double or missing coverage after binning and merging.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    std::vector<WindowVertex> vertices{{{4.5f, 4.5f, 0.5f}}};
    const float ring[8][2] = {{0.5f, 0.5f}, {4.5f, 0.5f}, {8.5f, 0.5f}, {8.5f, 4.5f},
                              {8.5f, 8.5f}, {4.5f, 8.5f}, {0.5f, 8.5f}, {0.5f, 4.5f}};
    for (const auto& r : ring) vertices.push_back({{r[0], r[1], 0.5f}});
    std::vector<uint32_t> indices;
    for (uint32_t i = 0; i < 8; ++i) indices.insert(indices.end(), {0, 1 + i, 1 + (i + 1) % 8});

    Framebuffer fb(8, 8, true);
    fb.clear(glm::vec4(0.0f), 1.0f);
    fb.clearCounts();
    PipelineState state;
    state.viewport = {0, 0, 8, 8};
    state.positionSpace = PositionSpace::Window;
    state.format = f;
    state.depth.compare = CompareOp::Always;
    state.depth.write = false;
    const WindowSpaceVertexShader vs;
    const ConstantColorShader ps;
    PipelineStatistics stats;
    ASSERT_TRUE(draw(
        fb, state,
        DrawCall<WindowSpaceVertexShader, ConstantColorShader>{vertices, indices, vs, ps}, stats));
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        EXPECT_EQ(fb.count(x, y), 1u) << "pixel (" << x << ", " << y << ")";
    EXPECT_EQ(stats.fragmentsWritten, 64u);
  }
}

}  // namespace
}  // namespace rast
