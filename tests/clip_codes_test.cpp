// Clip codes (pipeline/clip_codes.h): the block-wise two-term evaluation gives, vertex for vertex,
// the bits of the plane-by-plane reference outsideMask (clip.h), on both of its builds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pipeline/clip_codes.h"
#include "pipeline/state.h"

namespace rast {
namespace {

ScratchVector<ShadedVertex<0>> toVertices(const std::vector<glm::vec4>& positions) {
  ScratchVector<ShadedVertex<0>> v;
  for (const glm::vec4& p : positions) v.push_back({p, {}});
  return v;
}

void expectReferenceCodes(const std::vector<glm::vec4>& positions, const ClipPlanes& planes) {
  const ScratchVector<ShadedVertex<0>> vertices = toVertices(positions);
  const ScratchVector<VertexClipCodes> codes = computeClipCodes(vertices, planes);
  ASSERT_EQ(codes.size(), positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::dvec4 p(positions[i]);
    const bool finite =
        std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
    SCOPED_TRACE(::testing::Message() << "vertex " << i << " (" << p.x << ", " << p.y << ", "
                                      << p.z << ", " << p.w << ")");
    ASSERT_EQ(codes[i].finite, finite);
    ASSERT_EQ(codes[i].reject, finite ? outsideMask(planes.reject, p) : 0u);
    ASSERT_EQ(codes[i].clip, finite ? outsideMask(planes.clip, p) : 0u);
  }
}

// Points on, next to and far from the planes of a viewport: multiples of w at the NDC
// boundaries (exact zeros for the filter), their float neighbours, huge and tiny magnitudes, w of
// both signs and zero, and non-finite coordinates.
std::vector<glm::vec4> awkwardPositions(uint32_t seed, size_t randomCount) {
  std::mt19937 rng(seed);
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1e-30f, -1e-30f, 1e30f, -1e30f,
                            std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::infinity(),
                            std::numeric_limits<float>::quiet_NaN()};
  std::vector<glm::vec4> out;
  std::uniform_int_distribution<size_t> pick(0, std::size(specials) - 1);
  std::uniform_real_distribution<float> unit(-2.0f, 2.0f);
  std::uniform_int_distribution<int> exponent(-40, 40);
  for (size_t i = 0; i < randomCount; ++i) {
    const float w = (i % 3 == 0) ? specials[pick(rng)] : std::ldexp(unit(rng), exponent(rng));
    glm::vec4 p(0, 0, 0, w);
    for (int c = 0; c < 3; ++c) {
      switch (rng() % 5) {
        case 0: p[c] = w * (rng() % 2 ? 1.0f : -1.0f); break;  // on an NDC boundary
        case 1: p[c] = std::nextafter(w, rng() % 2 ? 1e38f : -1e38f); break;
        case 2: p[c] = specials[pick(rng)]; break;
        case 3: p[c] = 0.0f; break;
        default: p[c] = w * unit(rng) * (rng() % 4 == 0 ? 1e6f : 1.0f); break;
      }
    }
    out.push_back(p);
  }
  return out;
}

TEST(ClipCodes, EqualTheReferenceForViewportsAndBothFormats) {
  int cases = 0;
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()})
    for (const Viewport vp : {Viewport{0, 0, 1920, 1080}, Viewport{3, 7, 61, 33},
                              Viewport{-100, 50, 333, 1}, Viewport{0, 0, 0, 0}}) {
      PipelineState state;
      state.viewport = vp;
      state.format = format;
      const ClipPlanes planes = ClipPlanes::forState(state, ScreenMapping::forState(state));
      std::vector<AxisPlane> axis;
      ASSERT_TRUE(axisPlanes(planes, axis));
      // The depth planes are shared by both sets: 6 + 7 - 2 distinct planes (an empty viewport's
      // zero scale makes more of them equal).
      if (vp.width > 0) {
        EXPECT_EQ(axis.size(), 11u);
      }
      expectReferenceCodes(awkwardPositions(uint32_t(cases), 20000), planes);
      ++cases;
    }
  EXPECT_EQ(cases, 8);
}

// Planes made to pass (within rounding) through chosen points, and those points, so that a*x + b*w
// nearly cancels, the error bound does not decide, and the exact sum must.
TEST(ClipCodes, UndecidedVerticesTakeTheExactSum) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coefficient(0.1, 10.0);
  std::uniform_real_distribution<float> unit(0.5f, 2.0f);
  size_t undecided = 0;
  for (int round = 0; round < 50; ++round) {
    ClipPlanes planes;
    std::vector<glm::vec4> positions;
    for (size_t k = 0; k < planes.reject.size(); ++k) {
      const int axis = int(k % 3);
      const float x = unit(rng) * (k % 2 ? -1.0f : 1.0f), w = unit(rng);
      ClipPlane plane(0.0);
      plane[axis] = coefficient(rng);
      plane.w = -plane[axis] * double(x) / double(w);  // rounded: the plane misses (x, w) by a hair
      planes.reject[k] = plane;
      for (const float scale : {1.0f, 2.0f, 0.25f}) {
        for (const float px : {x, std::nextafter(x, 1e38f), std::nextafter(x, -1e38f)}) {
          glm::vec4 p(0.0f, 0.0f, 0.0f, w * scale);
          p[axis] = px * scale;
          const double t0 = plane[axis] * double(p[axis]), t1 = plane.w * double(p.w);
          const double bound = (std::abs(t0) + std::abs(t1)) * 0x1p-50 + 0x1p-1000;
          if (std::abs(t0 + t1) <= bound) ++undecided;
          positions.push_back(p);
        }
      }
    }
    for (size_t i = 0; i < planes.clip.size(); ++i) planes.clip[i] = planes.reject[(i + 1) % 6];
    expectReferenceCodes(positions, planes);
  }
  EXPECT_GT(undecided, 100u);
}

TEST(ClipCodes, PlanesOfAnotherShapeTakeTheGeneralPath) {
  PipelineState state;
  state.viewport = {0, 0, 640, 480};
  ClipPlanes planes = ClipPlanes::forState(state, ScreenMapping::forState(state));
  planes.reject[0] = ClipPlane(1.0, 1.0, 0.0, 0.5);  // two axes: not a two-term plane
  std::vector<AxisPlane> axis;
  EXPECT_FALSE(axisPlanes(planes, axis));
  expectReferenceCodes(awkwardPositions(99, 5000), planes);
}

// Every build of the plane tests this CPU runs gives the baseline's bits.
TEST(ClipCodes, EveryBuildOfThePlaneTestsAgrees) {
  using detail::ClipCodeIsa;
  const ClipCodeIsa best = detail::bestClipCodeIsa();
  if (best == ClipCodeIsa::Baseline) GTEST_SKIP() << "only the baseline build runs here";
  PipelineState state;
  state.viewport = {0, 0, 1920, 1080};
  const ClipPlanes planes = ClipPlanes::forState(state, ScreenMapping::forState(state));
  std::vector<AxisPlane> axis;
  ASSERT_TRUE(axisPlanes(planes, axis));
  const std::vector<glm::vec4> positions = awkwardPositions(5, 64 * 200);
  size_t compared = 0;
  for (const ClipCodeIsa isa : {ClipCodeIsa::Avx2, ClipCodeIsa::Avx512}) {
    if (isa > best) continue;
    SCOPED_TRACE(isa == ClipCodeIsa::Avx2 ? "AVX2" : "AVX-512");
    for (size_t b = 0; b < positions.size(); b += detail::kClipCodeBlock) {
      detail::ClipCodeBlock baseline, other;
      for (int i = 0; i < detail::kClipCodeBlock; ++i)
        for (int c = 0; c < 4; ++c) baseline.p[c][i] = other.p[c][i] = positions[b + size_t(i)][c];
      detail::testAxisPlanes(axis, baseline, ClipCodeIsa::Baseline);
      detail::testAxisPlanes(axis, other, isa);
      for (int i = 0; i < detail::kClipCodeBlock; ++i) {
        ASSERT_EQ(baseline.finite[i], other.finite[i]);
        ASSERT_EQ(baseline.outside[i], other.outside[i]);
        ASSERT_EQ(baseline.unsure[i], other.unsure[i]);
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, positions.size());
}

}  // namespace
}  // namespace rast
