// Watertightness: triangles sharing edges and vertices cover every sample of their union exactly
// once (fans and grids, in window space and across the near plane), and a closed mesh has as many
// front-facing as back-facing fragments at every pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "reference/watertight_cases.h"
#include "tests/union_reference.h"
#include "pipeline/draw.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

// The exact 2D geometry and the fan and grid generators are the reference's
// (reference/watertight_cases.h), which the precision tools share.
using reference::inClosedTriangle;
using reference::Mesh2D;
using reference::onSegment;
using reference::orient;
using reference::outlineEdges;
using reference::randomFan;
using reference::randomGrid;
using reference::SubPoint;

PipelineState countingState(int width, int height, FixedPointFormat format, PositionSpace space) {
  PipelineState s;
  s.viewport = {0, 0, width, height};
  s.format = format;
  s.positionSpace = space;
  // Every covered sample of every triangle is counted: no depth test, nothing hidden.
  s.depth.compare = CompareOp::Always;
  s.depth.write = false;
  return s;
}

template <class VS>
std::vector<uint32_t> drawCounts(const PipelineState& state, int width, int height,
                                 const std::vector<typename VS::Vertex>& vertices,
                                 const std::vector<uint32_t>& indices, const VS& vs,
                                 PipelineStatistics* statsOut = nullptr) {
  Framebuffer fb(width, height, true);
  PipelineStatistics stats;
  const ConstantColorShader ps;
  const Status s =
      draw(fb, state, DrawCall<VS, ConstantColorShader>{vertices, indices, vs, ps}, stats);
  EXPECT_TRUE(s.isOk()) << s.message();
  EXPECT_EQ(stats.fragmentsWritten, stats.samplesCovered);
  if (statsOut) *statsOut = stats;
  return fb.countPlane();
}

// ---------------------------------------------------------------------------------------------
// Window space, exact: vertices on the subpixel grid, so the snapped positions are known exactly
// and the reference is computed in integers with the top-left rule as Direct3D defines it.

// Whether the sample s is covered by the triangle: strictly inside, or exactly on a top edge
// (horizontal, the triangle below it) or a left edge (not horizontal, the triangle to its right).
bool coversSample(const std::array<SubPoint, 3>& v, SubPoint s) {
  const int64_t o = orient(v[0], v[1], v[2]);
  if (o == 0) return false;
  for (int i = 0; i < 3; ++i) {
    const SubPoint p = v[i], q = v[(i + 1) % 3], r = v[(i + 2) % 3];
    const int64_t e = orient(p, q, s);
    if (e != 0) {
      if ((e > 0) != (o > 0)) return false;
      continue;
    }
    const bool top = p.y == q.y && r.y > p.y;
    // orient(p, q, s) grows with s.x at the rate -(q.y - p.y): the interior (sign of o) lies to
    // the right of the edge when that rate has the sign of o.
    const bool left = p.y != q.y && ((-(q.y - p.y) > 0) == (o > 0));
    if (!top && !left) return false;
  }
  return true;
}

// Draws the triangles in window space and checks, sample by sample:
//   * the count equals the integer reference (sum over triangles of coversSample);
//   * no sample is covered twice;
//   * every sample inside the union and not on its outline is covered exactly once; this is the
//     watertightness property, independent of the reference's tie rule.
// Returns the number of samples strictly inside the union.
int expectWatertight(const Mesh2D& m, FixedPointFormat format, int width, int height,
                     const std::string& what) {
  const int64_t unit = format.subpixelsPerPixel();
  std::vector<WindowVertex> vertices;
  for (const SubPoint& p : m.vertices)
    vertices.push_back({glm::vec3(float(double(p.x) / unit), float(double(p.y) / unit), 0.5f)});
  const PipelineState state = countingState(width, height, format, PositionSpace::Window);
  PipelineStatistics stats;
  const std::vector<uint32_t> counts =
      drawCounts(state, width, height, vertices, m.indices, WindowSpaceVertexShader{}, &stats);

  auto sample = [&](int x, int y) { return SubPoint{x * unit + unit / 2, y * unit + unit / 2}; };
  auto pixelRange = [&](int64_t lo, int64_t hi, int limit) {
    const int a = std::max<int64_t>(0, lo / unit - 1), b = std::min<int64_t>(limit, hi / unit + 2);
    return std::pair<int, int>(a, b);
  };
  std::vector<uint32_t> reference(counts.size(), 0);
  std::vector<uint8_t> inUnion(counts.size(), 0), onOutline(counts.size(), 0);
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::array<SubPoint, 3> v = {m.vertices[m.indices[t]], m.vertices[m.indices[t + 1]],
                                       m.vertices[m.indices[t + 2]]};
    const auto [x0, x1] =
        pixelRange(std::min({v[0].x, v[1].x, v[2].x}), std::max({v[0].x, v[1].x, v[2].x}), width);
    const auto [y0, y1] =
        pixelRange(std::min({v[0].y, v[1].y, v[2].y}), std::max({v[0].y, v[1].y, v[2].y}), height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t i = size_t(y) * width + x;
        reference[i] += coversSample(v, sample(x, y));
        inUnion[i] |= inClosedTriangle(v, sample(x, y));
      }
  }
  for (const auto& [a, b] : outlineEdges(m.indices)) {
    const SubPoint p = m.vertices[a], q = m.vertices[b];
    const auto [x0, x1] = pixelRange(std::min(p.x, q.x), std::max(p.x, q.x), width);
    const auto [y0, y1] = pixelRange(std::min(p.y, q.y), std::max(p.y, q.y), height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        onOutline[size_t(y) * width + x] |= onSegment(p, q, sample(x, y));
  }

  int wrong = 0, interior = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      const bool strictlyInside = inUnion[i] && !onOutline[i];
      interior += strictlyInside;
      const bool ok =
          counts[i] == reference[i] && counts[i] <= 1 && (!strictlyInside || counts[i] == 1);
      if (!ok && ++wrong <= 5)
        ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") count " << counts[i]
                      << ", reference " << reference[i] << (strictlyInside ? ", inside" : "")
                      << (onOutline[i] ? ", on the outline" : "");
    }
  }
  EXPECT_EQ(wrong, 0) << what;
  uint64_t total = 0;
  for (uint32_t c : counts) total += c;
  EXPECT_EQ(stats.fragmentsWritten, total) << what;
  return interior;
}

class WatertightWindow : public ::testing::TestWithParam<FixedPointFormat> {};

TEST_P(WatertightWindow, FansCoverUnionOnce) {
  const FixedPointFormat format = GetParam();
  const uint64_t seed = 0xfa70000 + format.fractionBits;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  int interior = 0;
  for (int iter = 0; iter < 40; ++iter) {
    const Mesh2D m = randomFan(rng, format.subpixelsPerPixel(), 64, 64);
    interior +=
        expectWatertight(m, format, 64, 64, "fan " + std::to_string(iter) + " " + format.name());
    if (HasFailure()) return;
  }
  // Not vacuous: fans average a radius of 15 pixels, about 600 samples each.
  EXPECT_GT(interior, 40 * 300);
}

TEST_P(WatertightWindow, GridsCoverUnionOnce) {
  const FixedPointFormat format = GetParam();
  const uint64_t seed = 0x961d0000 + format.fractionBits;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int interior = 0;
  for (int iter = 0; iter < 40; ++iter) {
    // Cells from a third of a pixel (many triangles with no sample) to 12 pixels.
    const double cell = iter % 4 == 0 ? 0.3 + u(rng) : 2.0 + 10.0 * u(rng);
    const bool jitter = iter % 5 != 0;
    const Mesh2D m = randomGrid(rng, format.subpixelsPerPixel(), 64, 64, jitter, cell);
    interior += expectWatertight(
        m, format, 64, 64,
        "grid " + std::to_string(iter) + " " + format.name() + (jitter ? "" : " on samples"));
    if (HasFailure()) return;
  }
  // Not vacuous: most grids span much of the 64x64 framebuffer.
  EXPECT_GT(interior, 40 * 800);
}

INSTANTIATE_TEST_SUITE_P(Watertight, WatertightWindow,
                         ::testing::Values(FixedPointFormat::d24_4(), FixedPointFormat::d16_8()),
                         [](const auto& info) {
                           return info.param.fractionBits == 4 ? "d24_4" : "d16_8";
                         });

// ---------------------------------------------------------------------------------------------
// Clip space across the near plane. The reference clips each triangle in double and projects it;
// samples within a margin of the union's outline (outline edges and the near-plane cut) may go
// either way, every other sample must be covered exactly as often as the reference says: once
// inside (shared edges included), never outside.

using test_support::UnionReference;  // tests/union_reference.h

struct PositionVS {
  using Vertex = glm::vec4;
  static constexpr int kVaryings = 0;
  ShadedVertex<0> operator()(const glm::vec4& p) const { return {p, {}}; }
};

// Snapping moves each vertex by at most half a subpixel (1/32 pixel in 24.4); the vertices the
// clipper creates are rounded to float in clip space, which at the window coordinates here
// (< 1e4 pixels) adds < 1e-3 pixels. So samples farther than 1/16 pixel are decided.
constexpr double kSnapMargin = 1.0 / 16.0;

// What the clipper must do with each triangle, from the planes as viewport.h documents them.
struct ClipExpectation {
  uint64_t trivialReject = 0, clipped = 0;
};
ClipExpectation expectedClipping(const std::vector<glm::vec4>& v, const std::vector<uint32_t>& idx,
                                 int width, int height, FixedPointFormat format) {
  const double sx = 0.5 * width, sy = 0.5 * height, g = format.guardBandPixels();
  // window.x >= 0, <= width, window.y >= 0, <= height, depth >= 0, <= 1.
  const std::array<glm::dvec4, 6> reject = {
      glm::dvec4(sx, 0, 0, sx), glm::dvec4(-sx, 0, 0, sx),  glm::dvec4(0, -sy, 0, sy),
      glm::dvec4(0, sy, 0, sy), glm::dvec4(0, 0, 0.5, 0.5), glm::dvec4(0, 0, -0.5, 0.5)};
  // w >= 0, depth 0 and 1, and window coordinates within +-guard.
  const std::array<glm::dvec4, 7> clip = {glm::dvec4(0, 0, 0, 1),
                                          reject[4],
                                          reject[5],
                                          glm::dvec4(sx, 0, 0, sx + g),
                                          glm::dvec4(-sx, 0, 0, g - sx),
                                          glm::dvec4(0, -sy, 0, sy + g),
                                          glm::dvec4(0, sy, 0, g - sy)};
  ClipExpectation e;
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    unsigned all = ~0u, any = 0;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec4 p(v[idx[t + k]]);
      unsigned r = 0, c = 0;
      for (size_t i = 0; i < reject.size(); ++i) r |= (glm::dot(reject[i], p) < 0) << i;
      for (size_t i = 0; i < clip.size(); ++i) c |= (glm::dot(clip[i], p) < 0) << i;
      all &= r;
      any |= c;
    }
    if (all)
      ++e.trivialReject;
    else if (any)
      ++e.clipped;
  }
  return e;
}

// Returns the number of samples certainly inside the union.
int expectWatertightInClipSpace(const std::vector<glm::vec4>& v, const std::vector<uint32_t>& idx,
                                FixedPointFormat format, int width, int height,
                                const std::string& what) {
  const PipelineState state = countingState(width, height, format, PositionSpace::Clip);
  PipelineStatistics stats;
  const std::vector<uint32_t> counts =
      drawCounts(state, width, height, v, idx, PositionVS{}, &stats);
  const ClipExpectation e = expectedClipping(v, idx, width, height, format);
  EXPECT_EQ(stats.clipTrivialReject, e.trivialReject) << what;
  EXPECT_EQ(stats.clipClipped, e.clipped) << what;
  EXPECT_GT(e.clipped, 0u) << what << ": the geometry must cross the near plane";

  UnionReference ref(state.viewport);
  const auto outline = outlineEdges(idx);
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    std::array<glm::dvec4, 3> p;
    std::array<bool, 3> onOutline;
    for (int k = 0; k < 3; ++k) {
      p[k] = glm::dvec4(v[idx[t + k]]);
      const uint32_t a = idx[t + k], b = idx[t + (k + 1) % 3];
      onOutline[k] = std::find(outline.begin(), outline.end(),
                               std::pair(std::min(a, b), std::max(a, b))) != outline.end();
    }
    ref.addTriangle(p, onOutline);
  }
  int wrong = 0, inside = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const uint32_t n = counts[size_t(y) * width + x];
      const int expected = ref.classify(x + 0.5, y + 0.5, kSnapMargin);
      inside += expected == 1;
      const bool ok = expected < 0 ? n <= 1 : n == uint32_t(expected);
      if (!ok && ++wrong <= 5)
        ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") count " << n << ", reference "
                      << expected;
    }
  EXPECT_EQ(wrong, 0) << what;
  return inside;
}

// A plane a little below a perspective camera (so that where the near plane cuts it is in view):
// the fan's centre is in front, its rim reaches behind the eye.
TEST(WatertightNearPlane, FanAcrossNearPlaneCoversUnionOnce) {
  const uint64_t seed = 0x4ea70001;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr int W = 64, H = 48;
  const glm::dmat4 proj = glm::perspective(glm::radians(70.0), double(W) / H, 0.4, 30.0);
  int inside = 0;
  for (int iter = 0; iter < 16; ++iter) {
    const FixedPointFormat format =
        iter % 2 ? FixedPointFormat::d16_8() : FixedPointFormat::d24_4();
    const glm::dvec3 centre((u(rng) - 0.5) * 1.5, -0.4 + 0.25 * u(rng), -1.5 - 1.5 * u(rng));
    std::vector<glm::vec4> v = {glm::vec4(proj * glm::dvec4(centre, 1.0))};
    const int n = 6 + int(rng() % 10);
    const double start = u(rng) * 6.283185307179586;
    for (int k = 0; k < n; ++k) {
      const double angle = start + (k + 0.8 * (u(rng) - 0.5)) * 6.283185307179586 / n;
      const double radius = 2.0 + 3.0 * u(rng);
      // A plane through the centre, tilted so that it rises towards the eye.
      const glm::dvec3 p = centre +
                           glm::dvec3(radius * std::cos(angle), 0.0, radius * std::sin(angle)) +
                           glm::dvec3(0.0, 0.05 * radius * std::sin(angle), 0.0);
      v.push_back(glm::vec4(proj * glm::dvec4(p, 1.0)));
    }
    std::vector<uint32_t> idx;
    for (int k = 0; k < n; ++k)
      idx.insert(idx.end(), {0, uint32_t(1 + k), uint32_t(1 + (k + 1) % n)});
    inside += expectWatertightInClipSpace(v, idx, format, W, H,
                                          "fan " + std::to_string(iter) + " " + format.name());
  }
  // Not vacuous: the visible part of a fan covers several rows of the viewport on average.
  EXPECT_GT(inside, 16 * 400);
}

TEST(WatertightNearPlane, GridAcrossNearPlaneCoversUnionOnce) {
  const uint64_t seed = 0x4ea70002;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr int W = 64, H = 48;
  const glm::dmat4 proj = glm::perspective(glm::radians(70.0), double(W) / H, 0.4, 30.0);
  int inside = 0;
  for (int iter = 0; iter < 12; ++iter) {
    const FixedPointFormat format =
        iter % 2 ? FixedPointFormat::d16_8() : FixedPointFormat::d24_4();
    // A jittered grid on a ground plane from behind the eye (z = +1) to z = -7; jitter stays in
    // the plane so the surface remains planar and every cell convex.
    const int nx = 4 + int(rng() % 6), nz = 4 + int(rng() % 6);
    const double x0 = -3.0 - u(rng), x1 = 3.0 + u(rng), z0 = 1.0 + u(rng), z1 = -7.0 - u(rng);
    const double height = -0.12 - 0.2 * u(rng);
    std::vector<glm::vec4> v;
    for (int j = 0; j <= nz; ++j)
      for (int i = 0; i <= nx; ++i) {
        const double dx = (x1 - x0) / nx, dz = (z1 - z0) / nz;
        const double x = x0 + (i + 0.4 * (u(rng) - 0.5)) * dx;
        const double z = z0 + (j + 0.4 * (u(rng) - 0.5)) * dz;
        v.push_back(glm::vec4(proj * glm::dvec4(x, height, z, 1.0)));
      }
    std::vector<uint32_t> idx;
    for (int j = 0; j < nz; ++j)
      for (int i = 0; i < nx; ++i) {
        const uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
        if (rng() % 2)
          idx.insert(idx.end(), {a, b, c, a, c, d});
        else
          idx.insert(idx.end(), {a, b, d, b, c, d});
      }
    inside += expectWatertightInClipSpace(v, idx, format, W, H,
                                          "grid " + std::to_string(iter) + " " + format.name());
  }
  // Not vacuous: the visible part of the grid covers about a third of the viewport on average.
  EXPECT_GT(inside, 12 * 700);
}

// ---------------------------------------------------------------------------------------------
// A closed mesh: see /work/shared/data/meshes/README.md, "The watertightness invariant". At every
// sample, front-facing coverage equals back-facing coverage, and inside the silhouette both are
// at least 1. The camera stays outside the bounding sphere, so the near plane cuts nothing.

struct MeshCounts {
  std::vector<uint32_t> none, back, front;  // culling None, Back (front faces), Front (back faces)
};

MeshCounts drawMeshThreeWays(const Mesh& mesh, const glm::mat4& mvp, int size,
                             FixedPointFormat format) {
  MeshCounts out;
  TransformVertexShader vs;
  vs.modelViewProjection = mvp;
  for (const CullMode cull : {CullMode::None, CullMode::Back, CullMode::Front}) {
    PipelineState state = countingState(size, size, format, PositionSpace::Clip);
    state.cullMode = cull;
    PipelineStatistics stats;
    std::vector<uint32_t> counts =
        drawCounts(state, size, size, mesh.vertices, mesh.indices, vs, &stats);
    EXPECT_EQ(stats.clipClipped, 0u) << "the near plane must not cut the mesh";
    (cull == CullMode::None   ? out.none
     : cull == CullMode::Back ? out.back
                              : out.front) = std::move(counts);
  }
  return out;
}

void expectClosedMeshInvariant(const std::string& file, int size, FixedPointFormat format) {
  Mesh mesh;
  const Status s = loadObj(std::string(RASTER_SHARED_MESHES) + file, mesh);
  ASSERT_TRUE(s.isOk()) << s.message();
  const Camera framed = frameMesh(mesh);
  const float distance = glm::length(framed.eye - framed.target);
  const glm::vec3 directions[] = {
      {0, 0, 1}, {-1, 0, 0}, {0, 1, 0}, {1, 0.7f, -0.4f}, {-0.3f, -1, -0.8f}};
  for (const glm::vec3& d : directions) {
    Camera c = framed;
    c.eye = c.target + glm::normalize(d) * distance;
    c.up = std::abs(glm::normalize(d).y) > 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const MeshCounts m = drawMeshThreeWays(mesh, c.viewProjection(1.0f), size, format);
    const std::string what = file + " " + format.name() + " from (" + std::to_string(d.x) + ", " +
                             std::to_string(d.y) + ", " + std::to_string(d.z) + ")";
    int unequal = 0, holes = 0, silhouette = 0;
    for (size_t i = 0; i < m.none.size(); ++i) {
      const int x = int(i % size), y = int(i / size);
      if (m.back[i] != m.front[i] && ++unequal <= 5)
        ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") front-facing " << m.back[i]
                      << ", back-facing " << m.front[i];
      EXPECT_EQ(m.none[i], m.back[i] + m.front[i]) << what << " pixel " << x << ", " << y;
      if (m.none[i] > 0) {
        ++silhouette;
        if (m.back[i] == 0 && ++holes <= 5)
          ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") inside the silhouette ("
                        << m.none[i] << " fragments) has no front-facing one";
      }
    }
    EXPECT_EQ(unequal, 0) << what;
    EXPECT_EQ(holes, 0) << what;
    // frameMesh fits the bounding sphere to the view: the bunny fills a good part of it, whatever
    // the direction; this keeps the comparison above from passing on an empty image.
    EXPECT_GT(silhouette, size * size / 8) << what;
    EXPECT_LT(silhouette, size * size * 3 / 4) << what;
  }
}

TEST(WatertightClosedMesh, BunnyLowresFrontEqualsBack) {
  expectClosedMeshInvariant("/bunny_lowres.obj", 512, FixedPointFormat::d24_4());
  expectClosedMeshInvariant("/bunny_lowres.obj", 512, FixedPointFormat::d16_8());
}

// 75k triangles, median edge about 4 pixels at this size: many vertices shared by small
// triangles, and sub-pixel ones at the silhouette.
TEST(WatertightClosedMesh, BunnyFrontEqualsBack) {
  expectClosedMeshInvariant("/bunny.obj", 512, FixedPointFormat::d24_4());
}

}  // namespace
}  // namespace rast
