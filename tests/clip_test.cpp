// Clipping: near plane, trivial rejection, the guard band, non-finite input and w around 0.
//
// Coverage is compared with references computed here in double precision, independently of the
// pipeline: either exact configurations (half-planes, whole viewport) or a clipped-and-projected
// polygon with a margin around its outline inside which snapping may legitimately move the edge.
#include "tests/union_reference.h"
#include "pipeline/clip.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"

namespace rast {
namespace {

// The vertex buffer holds shaded vertices already: positions in the draw's position space.
template <int N>
struct PassThroughVS {
  using Vertex = ShadedVertex<N>;
  static constexpr int kVaryings = N;
  ShadedVertex<N> operator()(const Vertex& v) const { return v; }
};

PipelineState countingState(Viewport vp, FixedPointFormat format,
                            PositionSpace space = PositionSpace::Clip) {
  PipelineState s;
  s.viewport = vp;
  s.format = format;
  s.positionSpace = space;
  // Every covered sample of every triangle is counted: no depth test, nothing hidden.
  s.depth.compare = CompareOp::Always;
  s.depth.write = false;
  return s;
}

struct CountResult {
  std::vector<uint32_t> counts;
  PipelineStatistics stats;
};

template <int N>
CountResult drawCounts(const PipelineState& state, int width, int height,
                       const std::vector<ShadedVertex<N>>& vertices,
                       const std::vector<uint32_t>& indices) {
  Framebuffer fb(width, height, true);
  PipelineStatistics stats;
  const PassThroughVS<N> vs;
  const ConstantColorShader ps;
  const Status s = draw(
      fb, state, DrawCall<PassThroughVS<N>, ConstantColorShader>{vertices, indices, vs, ps}, stats);
  EXPECT_TRUE(s.isOk()) << s.message();
  return {fb.countPlane(), stats};
}

ShadedVertex<0> at(double x, double y, double z, double w) {
  return {glm::vec4(float(x), float(y), float(z), float(w)), {}};
}

uint64_t sum(const std::vector<uint32_t>& v) {
  uint64_t s = 0;
  for (uint32_t c : v) s += c;
  return s;
}

// ---------------------------------------------------------------------------------------------
// The union reference (clipped and projected in double) is in union_reference.h.
using test_support::UnionReference;

// Snapping moves each vertex by at most half a subpixel (1/32 pixel in 24.4), so every edge moves
// by at most that much; vertices the clipper creates are also rounded to float in clip space,
// which at the window coordinates used in these tests (< 1e4 pixels) adds < 1e-3 pixels.
constexpr double kSnapMargin = 1.0 / 16.0;

struct Comparison {
  int inside = 0, outside = 0, unknown = 0;
};

// Every sample: count <= 1; certainly inside: exactly 1; certainly outside: 0.
Comparison expectMatchesUnion(const std::vector<uint32_t>& counts, int width, int height,
                              const UnionReference& ref, const std::string& what) {
  Comparison c;
  int failures = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const uint32_t n = counts[size_t(y) * width + x];
      const int expected = ref.classify(x + 0.5, y + 0.5, kSnapMargin);
      const bool ok = expected < 0 ? n <= 1 : n == uint32_t(expected);
      if (expected < 0)
        ++c.unknown;
      else if (expected == 1)
        ++c.inside;
      else
        ++c.outside;
      if (!ok && ++failures <= 10)
        ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") count " << n << ", reference "
                      << expected << " (-1: near the outline, 0 or 1 allowed)";
    }
  }
  EXPECT_EQ(failures, 0) << what;
  return c;
}

// ---------------------------------------------------------------------------------------------
// Near plane: 0, 1, 2 and 3 vertices behind it.

constexpr int kVaryingCount = 3;
using V3 = ShadedVertex<kVaryingCount>;

// Varyings that are affine functions of the clip-space position: clipping interpolates both with
// the same parameter, so every vertex it creates must satisfy the same relations.
std::array<float, 3> affineVaryings(const glm::dvec4& p) {
  return {float(p.x + 2 * p.y), float(3 * p.z - p.w), float(0.25 * p.x - p.y + 4 * p.w)};
}

V3 makeV3(const glm::dvec4& p) {
  V3 v;
  v.position = glm::vec4(p);
  const glm::dvec4 exact(v.position);
  const auto a = affineVaryings(exact);
  for (int i = 0; i < 3; ++i) v.varyings[i] = a[i];
  return v;
}

using C3 = ClippedVertex<kVaryingCount>;
// Bit equality: of two clipper outputs, or of a clipper output and the input vertex it kept.
bool bitEqual(const C3& a, const C3& b) {
  return std::memcmp(&a.position, &b.position, sizeof(a.position)) == 0 &&
         std::memcmp(&a.varyings, &b.varyings, sizeof(a.varyings)) == 0;
}
bool bitEqual(const C3& a, const V3& b) { return bitEqual(a, C3{glm::dvec4(b.position), b.varyings}); }

// An orthographic-like triangle (w > 0 everywhere) with vertex k behind the near plane
// (z < -w) when bit k of `behindMask` is set.
std::array<V3, 3> nearTestTriangle(unsigned behindMask) {
  const std::array<glm::dvec2, 3> ndc = {glm::dvec2(-0.8, -0.7), glm::dvec2(0.9, -0.5),
                                         glm::dvec2(-0.1, 0.85)};
  const std::array<double, 3> w = {1.0, 2.0, 0.5};
  std::array<V3, 3> out;
  for (int k = 0; k < 3; ++k) {
    const double zNdc = (behindMask >> k) & 1 ? -2.5 : 0.2;
    out[k] = makeV3(glm::dvec4(ndc[k] * w[k], zNdc * w[k], w[k]));
  }
  return out;
}

class ClipNearPlane : public ::testing::TestWithParam<unsigned> {};

TEST_P(ClipNearPlane, PolygonVerticesOnPlaneWithInterpolatedVaryings) {
  const unsigned mask = GetParam();
  const int behind = std::popcount(mask);
  const std::array<V3, 3> tri = nearTestTriangle(mask);
  const PipelineState state = countingState({0, 0, 64, 64}, FixedPointFormat::d24_4());
  const ScreenMapping mapping = ScreenMapping::forState(state);
  const ClipPlanes planes = ClipPlanes::forState(state, mapping);
  const glm::dvec4 nearPlane(0, 0, 1, 1);  // z + w >= 0, i.e. depth >= 0

  // The near plane is clip plane 1; with every plane enabled the result must be the same, since
  // this triangle crosses no other plane.
  for (const unsigned planeMask : {1u << 1, (1u << ClipPlanes::kClipPlaneCount) - 1}) {
    ClipPolygon<kVaryingCount> poly;
    clipTriangle<kVaryingCount>({&tri[0], &tri[1], &tri[2]}, planes, planeMask, poly);
    // A triangle cut by one plane: 1 vertex behind leaves a quadrilateral, 2 behind a triangle.
    const int expectedCount[4] = {3, 4, 3, 0};
    ASSERT_EQ(poly.count, expectedCount[behind]) << "behind mask " << mask;

    int created = 0;
    for (int i = 0; i < poly.count; ++i) {
      const C3& v = poly.vertices[i];
      bool original = false;
      for (const V3& t : tri) original |= bitEqual(v, t);
      if (original) {
        EXPECT_GE(glm::dot(nearPlane, glm::dvec4(v.position)), 0.0) << "kept a vertex behind";
        continue;
      }
      ++created;
      const glm::dvec4 p(v.position);
      // On the plane up to the rounding of z and w to float (half an ulp each).
      EXPECT_LE(std::abs(p.z + p.w), 0x1p-23 * (std::abs(p.z) + std::abs(p.w)))
          << "vertex " << i << " not on the near plane";
      // Where the crossing edge meets the plane, computed here in double: the position and the
      // varyings must both be the interpolation at that parameter (float rounding only).
      bool matched = false;
      for (int e = 0; e < 3; ++e) {
        const glm::dvec4 a(tri[e].position), b(tri[(e + 1) % 3].position);
        const double da = glm::dot(nearPlane, a), db = glm::dot(nearPlane, b);
        if (!((da > 0 && db < 0) || (da < 0 && db > 0))) continue;
        const double t = da / (da - db);
        const glm::dvec4 expected = a + t * (b - a);
        bool same = true;
        for (int c = 0; c < 4; ++c)
          same &= std::abs(p[c] - expected[c]) <= 0x1p-22 * (std::abs(a[c]) + std::abs(b[c]));
        if (!same) continue;
        matched = true;
        for (int k = 0; k < kVaryingCount; ++k) {
          const double va = tri[e].varyings[k], vb = tri[(e + 1) % 3].varyings[k];
          EXPECT_NEAR(v.varyings[k], va + t * (vb - va), 0x1p-21 * (std::abs(va) + std::abs(vb)))
              << "varying " << k << " at vertex " << i;
        }
        // The affine relation between position and varyings survives interpolation.
        const auto rel = affineVaryings(p);
        for (int k = 0; k < kVaryingCount; ++k)
          EXPECT_NEAR(v.varyings[k], rel[k], 1e-5) << "varying " << k << " at vertex " << i;
      }
      EXPECT_TRUE(matched) << "vertex " << i << " is on no crossing edge";
    }
    // One new vertex per edge that crosses the plane: two whenever the plane cuts the triangle.
    EXPECT_EQ(created, behind == 1 || behind == 2 ? 2 : 0);

    // The polygon keeps the triangle's winding (all w > 0 here, so projection is valid).
    if (poly.count >= 3) {
      auto area = [&](auto get, int n) {
        double a = 0;
        for (int i = 0; i < n; ++i) {
          const glm::dvec2 p = get(i), q = get((i + 1) % n);
          a += p.x * q.y - q.x * p.y;
        }
        return a;
      };
      const double triArea =
          area([&](int i) { return glm::dvec2(tri[i].position) / double(tri[i].position.w); }, 3);
      const double polyArea = area(
          [&](int i) {
            return glm::dvec2(poly.vertices[i].position) / double(poly.vertices[i].position.w);
          },
          poly.count);
      EXPECT_GT(triArea * polyArea, 0.0) << "winding flipped";
    }
  }
}

TEST_P(ClipNearPlane, OutputTriangleCountsAndCoverage) {
  const unsigned mask = GetParam();
  const int behind = std::popcount(mask);
  const std::array<V3, 3> tri = nearTestTriangle(mask);
  constexpr int W = 64, H = 64;
  const PipelineState state = countingState({0, 0, W, H}, FixedPointFormat::d24_4());
  const std::vector<V3> vertices(tri.begin(), tri.end());
  const CountResult r = drawCounts<kVaryingCount>(state, W, H, vertices, {0, 1, 2});

  const PipelineStatistics& s = r.stats;
  EXPECT_EQ(s.inputTriangles, 1u);
  EXPECT_EQ(s.clipNonFinite, 0u);
  // All three behind one plane: rejected before clipping. Otherwise the near plane cuts off one
  // vertex (a quadrilateral: two triangles) or two (one triangle).
  EXPECT_EQ(s.clipTrivialReject, behind == 3 ? 1u : 0u);
  EXPECT_EQ(s.clipClipped, behind == 1 || behind == 2 ? 1u : 0u);
  const uint64_t expectedOut[4] = {1, 2, 1, 0};
  EXPECT_EQ(s.clipOutputTriangles, expectedOut[behind]);
  EXPECT_EQ(s.clipDegenerate, 0u);
  EXPECT_EQ(s.fragmentsWritten, sum(r.counts));

  UnionReference ref(state.viewport);
  std::array<glm::dvec4, 3> dv;
  for (int k = 0; k < 3; ++k) dv[k] = glm::dvec4(tri[k].position);
  ref.addTriangle(dv, {true, true, true});
  const Comparison c =
      expectMatchesUnion(r.counts, W, H, ref, "behind mask " + std::to_string(mask));
  if (behind < 3) {
    // The reference is not vacuous: most samples are decided, and the triangle covers many.
    EXPECT_GT(c.inside, 200);
    EXPECT_LT(c.unknown, c.inside / 2);
  } else {
    EXPECT_EQ(sum(r.counts), 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Clip, ClipNearPlane, ::testing::Range(0u, 8u),
                         [](const auto& info) { return "behind" + std::to_string(info.param); });

// A perspective camera and vertices behind the eye (w < 0): projecting them without clipping
// would draw the "external" triangle. The reference clips in double before projecting.
TEST(ClipNearPlaneTest, VerticesBehindTheEye) {
  constexpr int W = 64, H = 48;
  const glm::dmat4 proj = glm::perspective(glm::radians(60.0), double(W) / H, 0.5, 50.0);
  struct Case {
    std::array<glm::dvec3, 3> eye;
    uint64_t outputTriangles;
  };
  const Case cases[] = {
      // One vertex behind the eye: a quadrilateral.
      {{glm::dvec3(-1, -1, -3), glm::dvec3(2, -0.5, -4), glm::dvec3(0.3, 1.5, 1.0)}, 2},
      // Two behind the eye: a triangle.
      {{glm::dvec3(-1, -1, -3), glm::dvec3(2, -0.5, 2), glm::dvec3(0.3, 1.5, 1.0)}, 1},
      // One between the eye and the near plane (w > 0, depth < 0), one behind the eye.
      {{glm::dvec3(-0.4, -0.3, -0.2), glm::dvec3(2, -0.5, 3), glm::dvec3(0.3, 0.5, -6)}, 1},
  };
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    const PipelineState state = countingState({0, 0, W, H}, format);
    for (size_t ci = 0; ci < std::size(cases); ++ci) {
      std::vector<ShadedVertex<0>> v;
      std::array<glm::dvec4, 3> dv;
      for (int k = 0; k < 3; ++k) {
        const glm::dvec4 c = proj * glm::dvec4(cases[ci].eye[k], 1.0);
        v.push_back(at(c.x, c.y, c.z, c.w));
        dv[k] = glm::dvec4(v.back().position);
      }
      const CountResult r = drawCounts<0>(state, W, H, v, {0, 1, 2});
      EXPECT_EQ(r.stats.clipClipped, 1u) << "case " << ci;
      EXPECT_EQ(r.stats.clipOutputTriangles, cases[ci].outputTriangles) << "case " << ci;
      UnionReference ref(state.viewport);
      ref.addTriangle(dv, {true, true, true});
      const Comparison c = expectMatchesUnion(r.counts, W, H, ref,
                                              "case " + std::to_string(ci) + " " + format.name());
      EXPECT_GT(c.inside, 100) << "case " << ci;
    }
  }
}

// Two triangles sharing an edge that crosses the near plane: the crossing point is a symmetric
// function of the edge's endpoints, so both polygons get the same vertex and no sample along the
// shared edge is missed or hit twice.
TEST(ClipSharedEdge, SameCrossingVertexInBothPolygons) {
  const PipelineState state = countingState({0, 0, 64, 64}, FixedPointFormat::d24_4());
  const ScreenMapping mapping = ScreenMapping::forState(state);
  const ClipPlanes planes = ClipPlanes::forState(state, mapping);
  // a (behind the near plane) and c (in front) share the edge; b and d lie on either side.
  const V3 a = makeV3({0.3, -0.2, -1.7, 0.9}), c = makeV3({-0.45, 0.35, 0.1, 1.3});
  const V3 b = makeV3({0.8, 0.5, 0.2, 1.1}), d = makeV3({-0.7, -0.6, 0.3, 0.9});
  ClipPolygon<kVaryingCount> p1, p2;
  clipTriangle<kVaryingCount>({&a, &b, &c}, planes, 0x7F, p1);
  clipTriangle<kVaryingCount>({&c, &d, &a}, planes, 0x7F, p2);  // the edge walked c -> a
  ASSERT_GE(p1.count, 3);
  ASSERT_GE(p2.count, 3);
  int shared = 0;
  for (int i = 0; i < p1.count; ++i)
    for (int j = 0; j < p2.count; ++j)
      if (bitEqual(p1.vertices[i], p2.vertices[j]) && !bitEqual(p1.vertices[i], c)) ++shared;
  // Exactly one created vertex in common, bit for bit: where a-c crosses the near plane, although
  // one polygon walks the edge a -> c and the other c -> a.
  EXPECT_EQ(shared, 1);
}

TEST(ClipSharedEdge, NoCrackOrOverlapAlongEdgeCrossingNearPlane) {
  const uint64_t seed = 0x5eed0001;
  std::mt19937_64 rng(seed);
  std::cout << "[ seed ] ClipSharedEdge " << seed << "\n";
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr int W = 72, H = 56;
  const glm::dmat4 proj = glm::perspective(glm::radians(70.0), double(W) / H, 0.3, 40.0);
  int totalAlongEdge = 0;
  for (int iter = 0; iter < 24; ++iter) {
    const FixedPointFormat format =
        iter % 2 ? FixedPointFormat::d16_8() : FixedPointFormat::d24_4();
    const PipelineState state = countingState({0, 0, W, H}, format);
    // A planar quadrilateral (a square in a random tilted plane): corner a is near the eye or
    // behind it, c far in front, so the diagonal a-c crosses the near plane.
    const glm::dvec3 centre(0.6 * u(rng), 0.5 * u(rng), -2.0 - 0.5 * u(rng));
    const glm::dvec3 axisA = glm::normalize(glm::dvec3(0.4 * u(rng), 0.3 * u(rng), 1.0)) * 2.6;
    const glm::dvec3 axisB =
        glm::normalize(glm::cross(axisA, glm::dvec3(u(rng), 1.0, 0.2 * u(rng)))) * 1.5;
    const std::array<glm::dvec3, 4> eye = {centre + axisA, centre + axisB, centre - axisA,
                                           centre - axisB};
    std::vector<ShadedVertex<0>> v;
    std::array<glm::dvec4, 4> dv;
    for (int k = 0; k < 4; ++k) {
      const glm::dvec4 c = proj * glm::dvec4(eye[k], 1.0);
      v.push_back(at(c.x, c.y, c.z, c.w));
      dv[k] = glm::dvec4(v.back().position);
    }
    ASSERT_LT(dv[0].z, -dv[0].w) << "corner a must be behind the near plane";
    ASSERT_GT(dv[2].z, -dv[2].w) << "corner c must be in front of the near plane";
    const CountResult r = drawCounts<0>(state, W, H, v, {0, 1, 2, 0, 2, 3});
    UnionReference ref(state.viewport);
    ref.addTriangle({dv[0], dv[1], dv[2]}, {true, true, false});
    ref.addTriangle({dv[0], dv[2], dv[3]}, {false, true, true});
    const std::string what = "iteration " + std::to_string(iter) + " " + format.name();
    expectMatchesUnion(r.counts, W, H, ref, what);

    // Along the visible part of the shared edge: every certainly-inside sample within 1.5 pixels
    // of the edge is covered exactly once.
    int alongEdge = 0;
    // The shared edge, clipped to the near plane in double and projected.
    const double da = dv[0].z + dv[0].w, dc = dv[2].z + dv[2].w;
    const glm::dvec4 cut = dv[0] + (da / (da - dc)) * (dv[2] - dv[0]);
    const glm::dvec2 p0 = ref.project(cut), p1 = ref.project(dv[2]);
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        const glm::dvec2 s(x + 0.5, y + 0.5), e = p1 - p0;
        const double t = std::clamp(glm::dot(s - p0, e) / glm::dot(e, e), 0.0, 1.0);
        if (glm::length(s - (p0 + t * e)) > 1.5) continue;
        if (ref.classify(s.x, s.y, kSnapMargin) != 1) continue;
        ++alongEdge;
        EXPECT_EQ(r.counts[size_t(y) * W + x], 1u) << what << " pixel " << x << ", " << y;
      }
    }
    totalAlongEdge += alongEdge;
    EXPECT_EQ(r.stats.clipClipped, 2u) << what;
  }
  // Not vacuous: the shared edge is visible over many pixels (about 100 per quadrilateral).
  EXPECT_GT(totalAlongEdge, 1000);
}

// ---------------------------------------------------------------------------------------------
// Trivial rejection: all vertices outside one frustum plane.

TEST(ClipTrivialReject, EachFrustumPlane) {
  constexpr int W = 32, H = 32;
  const PipelineState state = countingState({0, 0, W, H}, FixedPointFormat::d24_4());
  struct Case {
    const char* plane;
    std::array<glm::dvec4, 3> v;
  };
  const Case cases[] = {
      {"left", {glm::dvec4(-1.2, 0, 0, 1), glm::dvec4(-5, 3, 0, 1), glm::dvec4(-3, -4, 0.5, 2)}},
      {"right", {glm::dvec4(1.01, -3, 0, 1), glm::dvec4(9, 3, 0, 1), glm::dvec4(5, 0, 0, 2)}},
      {"bottom", {glm::dvec4(-3, -1.5, 0, 1), glm::dvec4(3, -1.1, 0, 1), glm::dvec4(0, -9, 0, 2)}},
      {"top", {glm::dvec4(-3, 1.5, 0, 1), glm::dvec4(3, 1.1, 0, 1), glm::dvec4(0, 9, 0, 2)}},
      // Covering the whole viewport in x and y, but entirely nearer than the near plane.
      {"near", {glm::dvec4(-9, -9, -1.5, 1), glm::dvec4(9, -9, -1.1, 1), glm::dvec4(0, 9, -3, 1)}},
      {"far", {glm::dvec4(-9, -9, 1.5, 1), glm::dvec4(9, -9, 1.1, 1), glm::dvec4(0, 9, 3, 1)}},
      // Behind the eye: w < 0 puts every vertex outside the near plane.
      {"behind eye",
       {glm::dvec4(-1, -1, 0, -1), glm::dvec4(1, -1, 0, -1), glm::dvec4(0, 1, 0, -1)}},
  };
  for (const Case& c : cases) {
    std::vector<ShadedVertex<0>> v;
    for (const glm::dvec4& p : c.v) v.push_back(at(p.x, p.y, p.z, p.w));
    const CountResult r = drawCounts<0>(state, W, H, v, {0, 1, 2});
    EXPECT_EQ(r.stats.clipTrivialReject, 1u) << c.plane;
    EXPECT_EQ(r.stats.clipClipped, 0u) << c.plane;
    EXPECT_EQ(r.stats.clipOutputTriangles, 0u) << c.plane;
    EXPECT_EQ(sum(r.counts), 0u) << c.plane;
  }
  // Outside a different plane per vertex is not a trivial reject: this one covers the centre.
  std::vector<ShadedVertex<0>> v = {at(-3, -3, 0, 1), at(3, -3, 0, 1), at(0, 3, 0, 1)};
  const CountResult r = drawCounts<0>(state, W, H, v, {0, 1, 2});
  EXPECT_EQ(r.stats.clipTrivialReject, 0u);
  UnionReference ref(state.viewport);
  ref.addTriangle({glm::dvec4(-3, -3, 0, 1), glm::dvec4(3, -3, 0, 1), glm::dvec4(0, 3, 0, 1)},
                  {true, true, true});
  const Comparison c = expectMatchesUnion(r.counts, W, H, ref, "corner triangle");
  EXPECT_GT(c.inside, 500);
}

// ---------------------------------------------------------------------------------------------
// Guard band: huge coordinates and w ratios, against exact references.

// Compares a count image with an exact expectation, reporting the first few differences.
template <class F>
void expectImage(const std::vector<uint32_t>& counts, int width, int height, F expected,
                 const std::string& what) {
  int wrong = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const uint32_t n = counts[size_t(y) * width + x], e = expected(x, y);
      if (n != e && ++wrong <= 3)
        ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") count " << n << ", expected "
                      << e;
    }
  }
  EXPECT_EQ(wrong, 0) << what << ": wrong pixels";
}

struct GuardCase {
  const char* name;
  PositionSpace space;
  std::array<glm::dvec4, 3> v;
};

// Triangles whose intersection with the viewport is the whole viewport.
TEST(ClipGuardBand, HugeTrianglesCoverWholeViewportOnce) {
  constexpr int W = 40, H = 24;
  const GuardCase cases[] = {
      {"window 1e30",
       PositionSpace::Window,
       {glm::dvec4(-1e30, -1e30, 0.5, 1), glm::dvec4(3e30, -1e30, 0.5, 1),
        glm::dvec4(-1e30, 3e30, 0.5, 1)}},
      {"window 1e30 reversed",
       PositionSpace::Window,
       {glm::dvec4(-1e30, -1e30, 0.5, 1), glm::dvec4(-1e30, 3e30, 0.5, 1),
        glm::dvec4(3e30, -1e30, 0.5, 1)}},
      // Inside the 24.4 guard band (2^22), outside the 16.8 one (2^14).
      {"window 1e6",
       PositionSpace::Window,
       {glm::dvec4(-1e6, -1e6, 0.5, 1), glm::dvec4(3e6, -1e6, 0.5, 1),
        glm::dvec4(-1e6, 3e6, 0.5, 1)}},
      // w from 1e-20 to 1e25: projected positions at 1e20 and 1e5 NDC units.
      {"clip w ratio 1e45",
       PositionSpace::Clip,
       {glm::dvec4(-1, -1, 0, 1e-20), glm::dvec4(3, -1, 0, 1e-5),
        glm::dvec4(-1e30, 3e30, 0, 1e25)}},
      // One vertex a hair in front of the eye plane, one at w = 1e30.
      {"clip w 1e-38",
       PositionSpace::Clip,
       {glm::dvec4(-1e-30, -1e-30, 0, 1e-38), glm::dvec4(3e30, -1e30, 0, 1e30),
        glm::dvec4(-1, 3, 0, 1)}},
  };
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    for (const GuardCase& c : cases) {
      const PipelineState state = countingState({0, 0, W, H}, format, c.space);
      std::vector<ShadedVertex<0>> v;
      for (const glm::dvec4& p : c.v) v.push_back(at(p.x, p.y, p.z, p.w));
      const CountResult r = drawCounts<0>(state, W, H, v, {0, 1, 2});
      const std::string what = std::string(c.name) + " " + format.name();
      expectImage(
          r.counts, W, H, [](int, int) { return 1u; }, what);
      // Beyond the guard band the triangle must have gone through the clipper.
      const double maxCoord =
          std::max({std::abs(c.v[0].x / c.v[0].w), std::abs(c.v[1].x / c.v[1].w),
                    std::abs(c.v[2].x / c.v[2].w)}) *
          (c.space == PositionSpace::Clip ? W / 2.0 : 1.0);
      EXPECT_EQ(r.stats.clipClipped, maxCoord > format.guardBandPixels() ? 1u : 0u) << what;
    }
  }
}

// A triangle pair sharing an exactly vertical (or horizontal) edge through a column (row) of
// pixel centres, with the other vertices far beyond the guard band. Clipping keeps the shared
// edge's x (y) bit-exact, so the result is an exact half-plane each, and the top-left rule gives
// the column (row) on the edge to exactly one of them: the one whose interior lies to the right
// (below).
TEST(ClipGuardBand, ExactHalfPlanesAcrossSharedEdge) {
  constexpr int W = 41, H = 33;
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    for (const bool vertical : {true, false}) {
      for (const PositionSpace space : {PositionSpace::Window, PositionSpace::Clip}) {
        const PipelineState state = countingState({0, 0, W, H}, format, space);
        std::vector<ShadedVertex<0>> v;
        if (space == PositionSpace::Window) {
          // Window space: the edge is x = 20.5 (y = 16.5), through pixel centres.
          const double e = vertical ? 20.5 : 16.5;
          auto p = [&](double along, double across) {
            return vertical ? at(across, along, 0.5, 1) : at(along, across, 0.5, 1);
          };
          v = {p(-1e30, e), p(1e30, e), p(0, 1e30), p(0, -1e30)};
        } else {
          // Clip space: the edge is NDC x = 0 (y = 0), the centre column (row) of an odd-sized
          // viewport, between NDC -1e30 and 1e20; the other vertices at 1e25 and -1e15, with w
          // from 1e-30 to 1e-5.
          auto p = [&](double along, double across, double w) {
            return vertical ? at(across, along, 0, w) : at(along, -across, 0, w);
          };
          v = {p(-1, 0, 1e-30), p(1e10, 0, 1e-10), p(0, 1, 1e-25), p(0, -1e10, 1e-5)};
        }
        const CountResult positive = drawCounts<0>(state, W, H, v, {0, 1, 2});  // x > e (y > e)
        const CountResult negative = drawCounts<0>(state, W, H, v, {0, 1, 3});
        const std::string what = std::string(vertical ? "vertical " : "horizontal ") +
                                 (space == PositionSpace::Window ? "window " : "clip ") +
                                 format.name();
        const int edgePixel = vertical ? 20 : 16;
        expectImage(
            positive.counts, W, H,
            [&](int x, int y) { return (vertical ? x : y) >= edgePixel ? 1u : 0u; },
            what + ", interior on the positive side");
        expectImage(
            negative.counts, W, H,
            [&](int x, int y) { return (vertical ? x : y) < edgePixel ? 1u : 0u; },
            what + ", interior on the negative side");
        EXPECT_EQ(positive.stats.clipClipped, 1u) << what;
      }
    }
  }
}

// An edge along a line through the NDC origin (the viewport centre, a pixel corner here) with its
// endpoints at 2^e NDC units (w = 2^-e, e = 20, 40, 60: about 5e7, 5e13 and 5e19 pixels away):
// scaling by powers of two is exact, so whatever parameter the clipper computes, the vertices it
// creates keep y = s * x exactly for s = +-1, +-2, +-1/2, and snapping keeps the line. For slope
// +-2 and +-1/2 no sample lies on the line: the expected image is an exact half-plane. For slope
// +-1 samples lie on it: the pair sharing the edge must cover them exactly once between them.
TEST(ClipGuardBand, ExactDiagonalHalfPlanes) {
  constexpr int W = 48, H = 48;
  struct Slope {
    double dx, dy;
  };
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    for (const int e : {20, 40, 60}) {
      const double big = std::ldexp(1.0, -e);  // w of the far vertices
      const PipelineState state = countingState({0, 0, W, H}, format);
      for (const Slope d :
           {Slope{1, 2}, Slope{2, 1}, Slope{1, -2}, Slope{-2, 1}, Slope{1, 1}, Slope{1, -1}}) {
        // A and B: far along +-d. C and D: moderately far on either side, so their edges to A and B
        // run outside the viewport.
        const std::vector<ShadedVertex<0>> v = {at(d.dx, d.dy, 0, big), at(-d.dx, -d.dy, 0, big),
                                                at(-d.dy * 40, d.dx * 40, 0, 1),
                                                at(d.dy * 40, -d.dx * 40, 0, 1)};
        const CountResult left = drawCounts<0>(state, W, H, v, {0, 1, 2});
        const CountResult right = drawCounts<0>(state, W, H, v, {0, 1, 3});
        const std::string what = "2^" + std::to_string(e) + " slope " + std::to_string(d.dx) + "," +
                                 std::to_string(d.dy) + " " + format.name();
        std::vector<uint32_t> both(left.counts.size());
        for (size_t i = 0; i < both.size(); ++i) both[i] = left.counts[i] + right.counts[i];
        expectImage(
            both, W, H, [](int, int) { return 1u; }, what + ", the pair");
        // Samples off the line: C's side (side > 0) belongs to the left triangle only. Samples on
        // the line (slope +-1) go to either, checked by the pair above.
        auto side = [&](int x, int y) {
          const double nx = x + 0.5 - W / 2, ny = -(y + 0.5 - H / 2);  // NDC * 24: exact
          return d.dx * ny - d.dy * nx;
        };
        expectImage(
            left.counts, W, H,
            [&](int x, int y) {
              const double s = side(x, y);
              return s > 0 ? 1u : s < 0 ? 0u : left.counts[size_t(y) * W + x];
            },
            what + ", left");
        EXPECT_EQ(left.stats.clipClipped, 1u) << what;
      }
    }
  }
}

// Random triangles with w > 0 and one edge along a line through a random pixel corner (the NDC
// origin of a randomly offset viewport), its endpoints A and B at window distances from the
// viewport drawn from [minWindow, maxWindow]; the third vertex C between 1 and 1e6 NDC units away
// with w drawn from [minCW, maxCW]. A and B are (d, w) with small integer d and power-of-two w, so the
// edge passes exactly through the origin and is cut by the guard band at both ends.
//
// The reference is exact up to double rounding: with float homogeneous vertices h = (X, Y, W),
// each edge line L = h_i x h_j has components that are differences of two exact products, so
// rounded once; L . (x, y, 1) then gives the signed distance of a sample to the true edge without
// the cancellation that subtracting 1e30-sized coordinates would cause. Samples within
// kSnapMargin of an edge may go either way (snapping of the clipped vertices).
void expectRandomFarTrianglesMatchExactReference(uint64_t seed, double minWindow, double maxWindow,
                                                 double minCW, double maxCW, int iterations) {
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> dir(-9, 9);
  constexpr int FW = 48, FH = 40;
  int failedIterations = 0;
  for (int iter = 0; iter < iterations; ++iter) {
    const FixedPointFormat format =
        iter % 2 ? FixedPointFormat::d16_8() : FixedPointFormat::d24_4();
    const Viewport vp{-int(rng() % 40), -int(rng() % 40), 96, 80};
    const PipelineState state = countingState(vp, format);
    int dx = dir(rng), dy = dir(rng);
    if (dx == 0 && dy == 0) dx = 1;
    auto farW = [&] {  // w putting a vertex at direction d between minWindow and maxWindow
      const double window = minWindow * std::pow(maxWindow / minWindow, u(rng));
      return std::ldexp(1.0, -int(std::log2(window / (40.0 * std::hypot(dx, dy)))));
    };
    std::array<glm::dvec4, 3> h = {glm::dvec4(dx, dy, 0, farW()), glm::dvec4(-dx, -dy, 0, farW()),
                                   glm::dvec4()};
    // C: on a random side, at a random distance, with a random w.
    const double side = rng() % 2 ? 1.0 : -1.0;
    const double cw = minCW * std::pow(maxCW / minCW, u(rng));
    const double cDist = std::pow(10.0, 6 * u(rng));  // NDC units
    const double alpha = u(rng) * 6.283185307179586;
    glm::dvec2 cNdc = side * cDist * glm::dvec2(-dy, dx) / std::hypot(dx, dy) +
                      cDist * 0.7 * glm::dvec2(std::cos(alpha), std::sin(alpha));
    h[2] = glm::dvec4(cNdc.x * cw, cNdc.y * cw, 0, cw);
    std::vector<ShadedVertex<0>> v;
    for (const glm::dvec4& p : h) v.push_back(at(p.x, p.y, p.z, p.w));
    std::array<glm::dvec3, 3> hv;
    for (int i = 0; i < 3; ++i) {
      hv[i] = glm::dvec3(v[i].position.x, v[i].position.y, v[i].position.w);
      ASSERT_TRUE(std::isfinite(hv[i].x) && std::isfinite(hv[i].y) && hv[i].z > 0);
    }
    std::array<glm::dvec3, 3> lines;
    for (int i = 0; i < 3; ++i) lines[i] = glm::cross(hv[i], hv[(i + 1) % 3]);
    const double det = glm::dot(lines[0], hv[2]);
    if (det == 0) continue;

    const CountResult r = drawCounts<0>(state, FW, FH, v, {0, 1, 2});
    const std::string what = "iteration " + std::to_string(iter) + " " + format.name();
    int failures = 0, decided = 0;
    double closestWrong = std::numeric_limits<double>::infinity();
    for (int y = 0; y < FH; ++y) {
      for (int x = 0; x < FW; ++x) {
        const double sx = x + 0.5, sy = y + 0.5;
        const double nx = (sx - vp.x - 0.5 * vp.width) / (0.5 * vp.width);
        const double ny = -(sy - vp.y - 0.5 * vp.height) / (0.5 * vp.height);
        bool inside = true;
        double dist = std::numeric_limits<double>::infinity();
        for (const glm::dvec3& l : lines) {
          const double e = l.x * nx + l.y * ny + l.z;
          const double grad = std::hypot(l.x / (0.5 * vp.width), l.y / (0.5 * vp.height));
          dist = std::min(dist, std::abs(e) / grad);
          inside &= (e > 0) == (det > 0);
        }
        const uint32_t n = r.counts[size_t(y) * FW + x];
        if (dist <= kSnapMargin) {
          EXPECT_LE(n, 1u) << what;
          continue;
        }
        ++decided;
        if (n != (inside ? 1u : 0u)) {
          closestWrong = std::min(closestWrong, dist);
          if (++failures <= 2 && failedIterations < 5)
            ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") count " << n
                          << ", exact reference " << inside << ", " << dist
                          << " pixels from the nearest edge; vertices (clip x y w) " << hv[0].x
                          << " " << hv[0].y << " " << hv[0].z << " | " << hv[1].x << " " << hv[1].y
                          << " " << hv[1].z << " | " << hv[2].x << " " << hv[2].y << " " << hv[2].z
                          << ", viewport " << vp.x << " " << vp.y << " 96x80";
        }
      }
    }
    if (failures > 0 && ++failedIterations <= 5)
      ADD_FAILURE() << what << ": " << failures << " wrong samples, the closest " << closestWrong
                    << " px from an edge";
    EXPECT_GT(decided, FW * FH * 9 / 10) << what;
  }
  EXPECT_EQ(failedIterations, 0) << "of " << iterations << " triangles";
}

// Far, with C's w between 0.1 and 10.
TEST(ClipGuardBand, RandomFarTrianglesMatchExactReference) {
  expectRandomFarTrianglesMatchExactReference(0x6a4d0b5e, 1e5, 1e12, 0.1, 10, 200);
}

// As far, with C's w spanning 1e-18 .. 1e20 against A's and B's.
TEST(ClipGuardBand, RandomFarTrianglesHugeWRatioMatchExactReference) {
  expectRandomFarTrianglesMatchExactReference(0x6a4d0b5f, 1e5, 1e12, 1e-18, 1e20, 200);
}

// 1e13 .. 1e30 window units away.
TEST(ClipGuardBand, RandomHugeTrianglesMatchExactReference) {
  expectRandomFarTrianglesMatchExactReference(0x6a4d0b60, 1e13, 1e30, 0.1, 10, 200);
}

// ---------------------------------------------------------------------------------------------
// Non-finite positions.

TEST(ClipNonFinite, DroppedAndCounted) {
  constexpr int W = 32, H = 32;
  const PipelineState state = countingState({0, 0, W, H}, FixedPointFormat::d24_4());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<glm::vec4> bad = {{nan, 0, 0, 1}, {0, nan, 0, 1}, {0, 0, nan, 1},
                                      {0, 0, 0, nan}, {inf, 0, 0, 1}, {0, -inf, 0, 1},
                                      {0, 0, inf, 1}, {0, 0, 0, inf}, {0, 0, 0, -inf}};
  for (size_t b = 0; b < bad.size(); ++b) {
    // Two good triangles around the bad vertex; the middle one uses it.
    std::vector<ShadedVertex<0>> v = {at(-0.9, -0.9, 0, 1), at(0.9, -0.9, 0, 1), at(0.9, 0.9, 0, 1),
                                      at(-0.9, 0.9, 0, 1)};
    v.push_back({bad[b], {}});
    const std::vector<uint32_t> withBad = {0, 1, 2, 1, 4, 2, 0, 2, 3};
    const std::vector<uint32_t> withoutBad = {0, 1, 2, 0, 2, 3};
    const CountResult r = drawCounts<0>(state, W, H, v, withBad);
    const CountResult good = drawCounts<0>(state, W, H, v, withoutBad);
    EXPECT_EQ(r.stats.inputTriangles, 3u) << b;
    EXPECT_EQ(r.stats.clipNonFinite, 1u) << b;
    EXPECT_EQ(r.stats.clipOutputTriangles, 2u) << b;
    EXPECT_EQ(r.counts, good.counts) << "bad vertex " << b << " changed the image";

    // Only bad triangles: nothing reaches setup, nothing is drawn.
    const CountResult none = drawCounts<0>(state, W, H, v, {4, 0, 1, 2, 4, 3, 4, 4, 4});
    EXPECT_EQ(none.stats.inputTriangles, 3u) << b;
    EXPECT_EQ(none.stats.clipNonFinite, 3u) << b;
    EXPECT_EQ(none.stats.clipOutputTriangles, 0u) << b;
    EXPECT_EQ(none.stats.samplesCovered, 0u) << b;
    EXPECT_EQ(sum(none.counts), 0u) << b;
  }
}

// ---------------------------------------------------------------------------------------------
// w just above and below 0: a vertex in the eye plane (w = 0), a hair in front, a hair behind.
// The near plane removes it in every case; the visible part barely moves, so the images agree
// with each other and with the reference.
TEST(ClipNearW, JustAboveAndBelowZero) {
  constexpr int W = 64, H = 64;
  const double n = 0.5, f = 20;
  // glm::perspective's z row: z_clip = a * z_eye + b, w = -z_eye.
  const double a = -(f + n) / (f - n), b = -2 * f * n / (f - n);
  auto clipOf = [&](double x, double y, double w) {  // eye point with z_eye = -w, fov 90
    return glm::dvec4(x, y, a * -w + b, w);
  };
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    const PipelineState state = countingState({0, 0, W, H}, format);
    std::vector<uint32_t> first;
    for (const double w0 : {1e-30, 1e-7, 0.0, -1e-7, -1e-30, -0.0}) {
      const std::array<glm::dvec4, 3> p = {clipOf(-1.2, -0.8, 2.0), clipOf(1.5, -0.6, 3.0),
                                           clipOf(0.2, 0.3, w0)};
      std::vector<ShadedVertex<0>> v;
      std::array<glm::dvec4, 3> dv;
      for (int k = 0; k < 3; ++k) {
        v.push_back(at(p[k].x, p[k].y, p[k].z, p[k].w));
        dv[k] = glm::dvec4(v.back().position);
      }
      const CountResult r = drawCounts<0>(state, W, H, v, {0, 1, 2});
      const std::string what = "w " + std::to_string(w0) + " " + format.name();
      EXPECT_EQ(r.stats.clipClipped, 1u) << what;
      EXPECT_EQ(r.stats.clipOutputTriangles, 2u) << what;
      EXPECT_EQ(r.stats.clipDegenerate, 0u) << what;
      UnionReference ref(state.viewport);
      ref.addTriangle(dv, {true, true, true});
      const Comparison c = expectMatchesUnion(r.counts, W, H, ref, what);
      EXPECT_GT(c.inside, 300) << what;
      if (first.empty())
        first = r.counts;
      else
        EXPECT_EQ(r.counts, first) << what << " differs from w = 1e-30";
    }
  }
}

}  // namespace
}  // namespace rast
