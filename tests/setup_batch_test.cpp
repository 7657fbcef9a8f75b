// SetupBatch (several triangles at a time, vectorised) against setupTriangle (one at a time):
// the same triangles kept, in the same order, with the same bits in every field, and the same
// counters, for both builds of the batch's loops, both precisions, every cull mode, winding, fill
// rule and MSAA reach, with and without varyings.
#include "pipeline/setup_batch.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "rasterizer/sample_pattern.h"

namespace rast {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;

// Triangles as the front end hands them to setup: unclipped, so inside the guard band, but
// otherwise anything: small and large, both windings, zero area, off the clip rectangle, on
// quarter-pixel grids (ties with pixel centres and the fill rule), with non-finite corners.
template <int N>
std::vector<ShadedVertex<N>> randomTriangles(int count, const ScreenMapping& mapping,
                                             FixedPointFormat format, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double guard = format.guardBandPixels() * 0.99;
  std::vector<ShadedVertex<N>> v;
  auto toClip = [&](double wx, double wy, double z, double w) {
    ShadedVertex<N> s;
    s.position = glm::vec4(float((wx - mapping.offset.x) / mapping.scale.x * w),
                           float((wy - mapping.offset.y) / mapping.scale.y * w),
                           float((z - mapping.offset.z) / mapping.scale.z * w), float(w));
    for (int k = 0; k < N; ++k) s.varyings[k] = float(unit(rng) * 8 - 4);
    return s;
  };
  for (int t = 0; t < count; ++t) {
    const int kind = int(unit(rng) * 10);
    const double cx = unit(rng) * (kWidth + 200) - 100, cy = unit(rng) * (kHeight + 200) - 100;
    // kind 0: under two pixels across, which setup tests at the centres in their bounds.
    const double size = kind == 0  ? 0.1 + unit(rng) * 1.1
                        : kind < 4 ? 0.5 + unit(rng) * 20
                        : kind < 7 ? unit(rng) * 2000
                                   : guard;
    std::array<double, 3> x, y;
    for (int i = 0; i < 3; ++i) {
      x[i] = std::clamp(cx + (unit(rng) - 0.5) * 2 * size, -guard, guard);
      y[i] = std::clamp(cy + (unit(rng) - 0.5) * 2 * size, -guard, guard);
      if (kind == 3) {  // on a quarter-pixel grid
        x[i] = std::round(x[i] * 4) / 4;
        y[i] = std::round(y[i] * 4) / 4;
      }
    }
    if (kind == 7) {  // zero area: a repeated corner, or three corners on a line
      if (unit(rng) < 0.5) {
        x[2] = x[0];
        y[2] = y[0];
      } else {
        x[1] = x[0] + 3;
        x[2] = x[0] + 7;
        y[1] = y[2] = y[0];
      }
    }
    for (int i = 0; i < 3; ++i) {
      double w = 0.05 + unit(rng) * 10;
      double z = unit(rng);
      v.push_back(toClip(x[i], y[i], z, w));
    }
    if (kind == 8 && unit(rng) < 0.5) {  // a corner that is not finite
      ShadedVertex<N>& bad = v[v.size() - 1 - size_t(unit(rng) * 3)];
      const float values[] = {std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::infinity(), 0.0f};
      const int which = int(unit(rng) * 3);
      if (which == 2) bad.position.w = 0;  // 1/w is infinite
      else bad.position[int(unit(rng) * 4)] = values[which];
    }
  }
  return v;
}

template <int N>
void expectSameTriangle(const SetupTriangle<N>& a, const SetupTriangle<N>& b, size_t i) {
  auto same = [](const PlaneEquation& p, const PlaneEquation& q) {
    return std::bit_cast<uint32_t>(p.at0) == std::bit_cast<uint32_t>(q.at0) &&
           std::bit_cast<uint32_t>(p.ddx) == std::bit_cast<uint32_t>(q.ddx) &&
           std::bit_cast<uint32_t>(p.ddy) == std::bit_cast<uint32_t>(q.ddy);
  };
  SCOPED_TRACE(testing::Message() << "triangle " << i);
  for (int e = 0; e < 3; ++e) {
    EXPECT_EQ(a.edges[e].a, b.edges[e].a);
    EXPECT_EQ(a.edges[e].b, b.edges[e].b);
    EXPECT_EQ(a.edges[e].c, b.edges[e].c);
  }
  EXPECT_EQ(a.bounds, b.bounds);
  EXPECT_EQ(a.primitiveId(), b.primitiveId());
  EXPECT_EQ(a.frontFacing(), b.frontFacing());
  EXPECT_TRUE(same(a.depth, b.depth));
  if constexpr (N > 0) {
    EXPECT_TRUE(same(a.invW, b.invW));
    for (int k = 0; k < N; ++k) EXPECT_TRUE(same(a.varyingsOverW[k], b.varyingsOverW[k]));
  }
}

template <int N>
void compareWithSetupTriangle(detail::SetupIsa isa) {
  PipelineState state;
  state.viewport = {0, 0, kWidth, kHeight};
  const ScreenMapping mapping = ScreenMapping::forState(state);
  const PixelRect clipRects[] = {{0, 0, kWidth, kHeight}, {300, 200, 301, 900}};
  uint32_t seed = 1;
  size_t drawn = 0, kinds[4] = {};
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()})
    for (const CullMode cull : {CullMode::None, CullMode::Back, CullMode::Front})
      for (const FrontFace face : {FrontFace::Clockwise, FrontFace::CounterClockwise})
        for (const FillRule rule : {FillRule::TopLeft, FillRule::BottomLeft})
          for (const int samples : {1, 4})
            for (const PixelRect& clip : clipRects) {
              SCOPED_TRACE(testing::Message() << format.name() << " cull " << int(cull) << " face "
                                              << int(face) << " rule " << int(rule) << " samples "
                                              << samples << " clip x0 " << clip.x0);
              const SetupContext ctx{mapping,
                                     format,
                                     clip,
                                     cull,
                                     face,
                                     rule,
                                     SamplePattern::forCount(samples).reach(format),
                                     RasterMode::FixedPoint};
              const std::vector<ShadedVertex<N>> v =
                  randomTriangles<N>(2000, mapping, format, seed++);

              std::vector<SetupTriangle<N>> expected;
              PipelineStatistics expectedStats;
              FloatEdges unused;
              for (size_t t = 0; 3 * t < v.size(); ++t) {
                SetupTriangle<N> triangle;
                if (setupTriangle<N, ShadedVertex<N>>({&v[3 * t], &v[3 * t + 1], &v[3 * t + 2]},
                                                      ctx, uint32_t(t), triangle, unused,
                                                      expectedStats))
                  expected.push_back(triangle);
              }

              ScratchVector<SetupTriangle<N>> got;
              got.reserve(v.size() / 3);
              PipelineStatistics stats;
              SetupBatch<N> batch(ctx, isa);
              // Flushed when full, and also early now and then, as a clipped triangle does.
              for (size_t t = 0; 3 * t < v.size(); ++t) {
                batch.add({&v[3 * t], &v[3 * t + 1], &v[3 * t + 2]}, uint32_t(t));
                if (batch.full() || t % 37 == 0) batch.flush(got, stats);
              }
              batch.flush(got, stats);

              EXPECT_EQ(stats, expectedStats);
              ASSERT_EQ(got.size(), expected.size());
              for (size_t i = 0; i < got.size(); ++i) expectSameTriangle(got[i], expected[i], i);
              drawn += got.size();
              kinds[0] += stats.clipDegenerate;
              kinds[1] += stats.setupZeroArea;
              kinds[2] += stats.setupCulledBack + stats.setupCulledFront;
              kinds[3] += stats.setupNoSamples;
            }
  // Every way out of setup was taken, many times.
  EXPECT_GT(drawn, 10000u);
  for (size_t k : kinds) EXPECT_GT(k, 1000u);
}

// The builds this CPU runs: baseline always, then AVX2 and AVX-512 where present.
TEST(SetupBatch, EqualsSetupTriangleBaselineBuild) {
  compareWithSetupTriangle<0>(detail::SetupIsa::Baseline);
  compareWithSetupTriangle<3>(detail::SetupIsa::Baseline);
}

TEST(SetupBatch, EqualsSetupTriangleAvx2Build) {
  if (detail::bestSetupIsa() < detail::SetupIsa::Avx2) GTEST_SKIP() << "no AVX2 on this CPU";
  compareWithSetupTriangle<0>(detail::SetupIsa::Avx2);
  compareWithSetupTriangle<3>(detail::SetupIsa::Avx2);
}

TEST(SetupBatch, EqualsSetupTriangleAvx512Build) {
  if (detail::bestSetupIsa() < detail::SetupIsa::Avx512) GTEST_SKIP() << "no AVX-512 on this CPU";
  compareWithSetupTriangle<0>(detail::SetupIsa::Avx512);
  compareWithSetupTriangle<3>(detail::SetupIsa::Avx512);
}

// The primitive id and the facing flag share a word: every id a draw can give (below 2^28, and
// the 31 bits the word keeps for it) comes back with either facing.
TEST(SetupTriangleLayout, PrimitiveIdAndFacingShareAWord) {
  for (const uint32_t id : {0u, 1u, (1u << 28) - 1, (1u << 31) - 1})
    for (const bool front : {false, true}) {
      SetupTriangle<0> t;
      t.setPrimitive(id, front);
      EXPECT_EQ(t.primitiveId(), id);
      EXPECT_EQ(t.frontFacing(), front);
    }
}

}  // namespace
}  // namespace rast
