// Watertightness at scale, in every fixed-point precision: fans of 3 to 1000 triangles around a
// vertex at a random subpixel position, random triangulations of the whole screen, and every
// closed mesh of ../shared/data/meshes at hundreds of random camera poses, many of them with the
// near plane cutting through the mesh.
//
// Under AddressSanitizer (__SANITIZE_ADDRESS__, which GCC defines) the counts are reduced; the
// properties checked are the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "pipeline/draw.h"
#include "scene/mesh.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/transform.h"

namespace rast {
namespace {

#ifdef __SANITIZE_ADDRESS__
constexpr int kScale = 8;  // one eighth of the work
#else
constexpr int kScale = 1;
#endif

struct PositionVS {
  using Vertex = glm::vec4;
  static constexpr int kVaryings = 0;
  ShadedVertex<0> operator()(const glm::vec4& p) const { return {p, {}}; }
};

PipelineState countingState(int width, int height, FixedPointFormat format, PositionSpace space) {
  PipelineState s;
  s.viewport = {0, 0, width, height};
  s.format = format;
  s.positionSpace = space;
  s.depth.compare = CompareOp::Always;  // every covered sample counts
  s.depth.write = false;
  return s;
}

template <class VS>
std::vector<uint32_t> drawCounts(const PipelineState& state,
                                 const std::vector<typename VS::Vertex>& vertices,
                                 const std::vector<uint32_t>& indices, const VS& vs,
                                 PipelineStatistics& stats) {
  Framebuffer fb(state.viewport.width, state.viewport.height, true);
  const ConstantColorShader ps;
  const Status s =
      draw(fb, state, DrawCall<VS, ConstantColorShader>{vertices, indices, vs, ps}, stats);
  EXPECT_TRUE(s.isOk()) << s.message();
  return fb.countPlane();
}

// ---------------------------------------------------------------------------------------------
// Window space on the subpixel grid: exact integer references.

struct SubPoint {
  int64_t x, y;
};

int64_t orient(SubPoint a, SubPoint b, SubPoint c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

std::vector<glm::vec4> toWindowVertices(const std::vector<SubPoint>& points, FixedPointFormat f) {
  std::vector<glm::vec4> v;
  for (const SubPoint& p : points)
    v.push_back({float(std::ldexp(double(p.x), -f.fractionBits)),
                 float(std::ldexp(double(p.y), -f.fractionBits)), 0.5f, 1.0f});
  return v;
}

// A fan of n triangles around a centre at a random subpixel position: rim points at increasing
// angles, every triangle clockwise on screen (a rim point that would break that is drawn again),
// each listed with a random winding. Returns the fan and, per pixel, whether its sample lies
// strictly inside the fan's outline (the rim polygon, a star around the centre).
struct Fan {
  std::vector<SubPoint> points;
  std::vector<uint32_t> indices;
};

Fan randomFan(std::mt19937_64& rng, int n, FixedPointFormat f, int width, int height) {
  const int64_t unit = f.subpixelsPerPixel();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double maxRadius = std::min(width, height) * 0.45;
  const SubPoint c{int64_t((width * 0.5 + (u(rng) - 0.5) * 8) * unit),
                   int64_t((height * 0.5 + (u(rng) - 0.5) * 8) * unit)};
  for (;;) {
  Fan fan;
  fan.points.push_back(c);
  const double start = u(rng) * 2 * M_PI;
  for (int k = 0; k < n; ++k) {
    const double angle = start + (k + 0.8 * (u(rng) - 0.5)) * 2 * M_PI / n;
    // Long spokes where the angles are dense, so consecutive rim points stay apart.
    const double radius = (0.3 + 0.7 * u(rng)) * maxRadius * unit;
    fan.points.push_back({c.x + std::llround(radius * std::cos(angle)),
                          c.y + std::llround(radius * std::sin(angle))});
  }
  // Drop rim points that rounding put out of angular order.
  std::vector<SubPoint> rim(fan.points.begin() + 1, fan.points.end());
  for (bool changed = true; changed && rim.size() >= 3;) {
    changed = false;
    for (size_t k = 0; k < rim.size(); ++k) {
      const SubPoint a = rim[k], b = rim[(k + 1) % rim.size()];
      if (orient(c, a, b) <= 0 && rim.size() > 3) {
        rim.erase(rim.begin() + ptrdiff_t((k + 1) % rim.size()));
        changed = true;
        break;
      }
    }
  }
  bool convexWedges = rim.size() >= 3;
  for (size_t k = 0; k < rim.size(); ++k) convexWedges &= orient(c, rim[k], rim[(k + 1) % rim.size()]) > 0;
  if (!convexWedges) continue;  // a wedge of pi or more (few spokes): draw the fan again
  fan.points.resize(1);
  fan.points.insert(fan.points.end(), rim.begin(), rim.end());
  const uint32_t m = uint32_t(rim.size());
  for (uint32_t k = 0; k < m; ++k) {
    const uint32_t a = 1 + k, b = 1 + (k + 1) % m;
    if (rng() % 2) fan.indices.insert(fan.indices.end(), {0, a, b});
    else fan.indices.insert(fan.indices.end(), {0, b, a});
  }
  return fan;
  }
}

// Every sample strictly inside the fan (inside some triangle or on a spoke, not on the rim) is
// covered exactly once; samples outside or on the rim at most once. Returns the number inside.
int expectFanWatertight(const Fan& fan, FixedPointFormat f, int width, int height,
                         const std::string& what) {
  PipelineStatistics stats;
  const std::vector<uint32_t> counts =
      drawCounts(countingState(width, height, f, PositionSpace::Window),
                 toWindowVertices(fan.points, f), fan.indices, PositionVS{}, stats);
  const int64_t unit = f.subpixelsPerPixel();
  const SubPoint c = fan.points[0];
  const size_t m = fan.points.size() - 1;
  int wrong = 0, inside = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const SubPoint s{x * unit + unit / 2, y * unit + unit / 2};
      // Strictly inside the star polygon: in the closed wedge of some spoke pair and strictly
      // on the inner side of that rim edge.
      bool strictlyInside = false, onOrInside = false;
      for (size_t k = 0; k < m && !strictlyInside; ++k) {
        const SubPoint a = fan.points[1 + k], b = fan.points[1 + (k + 1) % m];
        if (orient(c, a, s) < 0 || orient(c, b, s) > 0) continue;  // not in this wedge
        const int64_t rimSide = orient(a, b, s);
        strictlyInside = rimSide > 0;
        onOrInside |= rimSide >= 0;
      }
      const uint32_t n = counts[size_t(y) * width + x];
      inside += strictlyInside;
      const bool ok = strictlyInside ? n == 1 : (onOrInside ? n <= 1 : n == 0);
      if (!ok && ++wrong <= 3)
        ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") count " << n
                      << (strictlyInside ? ", strictly inside" : onOrInside ? ", on the rim" : ", outside");
    }
  EXPECT_EQ(wrong, 0) << what;
  return inside;
}

class ScalePrecision : public ::testing::TestWithParam<int> {
 protected:
  FixedPointFormat format() const { return FixedPointFormat::withFractionBits(GetParam()); }
};

TEST_P(ScalePrecision, FansOf3To1000Triangles) {
  const FixedPointFormat f = format();
  const uint64_t seed = 0xfa5ca1e0 + GetParam();
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  constexpr int W = 160, H = 120;
  int inside = 0, fans = 0;
  for (const int n : {3, 3, 4, 5, 7, 12, 31, 64, 200, 500, 1000}) {
    if (kScale > 1 && n > 200) continue;
    const Fan fan = randomFan(rng, n, f, W, H);
    inside += expectFanWatertight(fan, f, W, H, f.name() + " fan of " + std::to_string(n));
    ++fans;
    if (HasFailure()) return;
  }
  // Not vacuous: rims average 0.65 * 54 pixels from the centre; a fan of few spokes is a
  // polygon inside that circle, so about 3,000 samples a fan over this mix.
  EXPECT_GT(inside, fans * 2000);
}

// A random triangulation of a rectangle that contains the screen: its four corners, then
// random points on the subpixel grid inserted one by one, each splitting the triangle that
// strictly contains it into three (points on an edge are skipped). Slivers abound. Every sample
// of the screen lies in the rectangle's interior, so each is covered exactly once.
struct Triangulation {
  std::vector<SubPoint> points;
  std::vector<std::array<uint32_t, 3>> triangles;  // clockwise on screen
};

Triangulation randomTriangulation(std::mt19937_64& rng, SubPoint lo, SubPoint hi, int insertions) {
  Triangulation t;
  t.points = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  t.triangles = {{0, 1, 2}, {0, 2, 3}};  // clockwise with y down
  std::uniform_int_distribution<int64_t> ux(lo.x + 1, hi.x - 1), uy(lo.y + 1, hi.y - 1);
  for (int i = 0; i < insertions; ++i) {
    const SubPoint p{ux(rng), uy(rng)};
    for (size_t k = 0; k < t.triangles.size(); ++k) {
      const auto [a, b, c] = t.triangles[k];
      const SubPoint pa = t.points[a], pb = t.points[b], pc = t.points[c];
      const int64_t e0 = orient(pa, pb, p), e1 = orient(pb, pc, p), e2 = orient(pc, pa, p);
      if (e0 < 0 || e1 < 0 || e2 < 0) continue;
      if (e0 > 0 && e1 > 0 && e2 > 0) {
        const uint32_t n = uint32_t(t.points.size());
        t.points.push_back(p);
        t.triangles[k] = {a, b, n};
        t.triangles.push_back({b, c, n});
        t.triangles.push_back({c, a, n});
      }
      break;  // on an edge or a vertex: skipped
    }
  }
  return t;
}

TEST_P(ScalePrecision, RandomTriangulationsOfTheScreenCoverEachSampleOnce) {
  const FixedPointFormat f = format();
  const int64_t unit = f.subpixelsPerPixel();
  const uint64_t seed = 0x7219a000 + GetParam();
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  constexpr int W = 160, H = 120;
  for (int iter = 0; iter < 6; ++iter) {
    // The screen's own corners, or a rectangle reaching up to 40 pixels beyond them.
    const bool exact = iter % 2 == 0;
    const SubPoint lo = exact ? SubPoint{0, 0}
                              : SubPoint{-int64_t(rng() % (40 * unit)), -int64_t(rng() % (40 * unit))};
    const SubPoint hi = exact ? SubPoint{W * unit, H * unit}
                              : SubPoint{W * unit + int64_t(rng() % (40 * unit)),
                                         H * unit + int64_t(rng() % (40 * unit))};
    const int insertions = (iter < 2 ? 200 : 2000) / kScale;
    const Triangulation t = randomTriangulation(rng, lo, hi, insertions);
    std::vector<uint32_t> indices;
    for (const auto& tri : t.triangles) {
      if (rng() % 2) indices.insert(indices.end(), {tri[0], tri[1], tri[2]});
      else indices.insert(indices.end(), {tri[0], tri[2], tri[1]});
    }
    PipelineStatistics stats;
    const std::vector<uint32_t> counts =
        drawCounts(countingState(W, H, f, PositionSpace::Window), toWindowVertices(t.points, f),
                   indices, PositionVS{}, stats);
    const std::string what = f.name() + " triangulation " + std::to_string(iter) + " of " +
                             std::to_string(t.triangles.size()) + " triangles";
    int wrong = 0;
    for (size_t i = 0; i < counts.size(); ++i)
      if (counts[i] != 1 && ++wrong <= 3)
        ADD_FAILURE() << what << ": pixel (" << i % W << ", " << i / W << ") count " << counts[i];
    EXPECT_EQ(wrong, 0) << what;
    EXPECT_EQ(stats.fragmentsWritten, uint64_t(W * H)) << what;
    EXPECT_GT(t.triangles.size(), size_t(insertions)) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Watertight, ScalePrecision, ::testing::Range(1, 9),
                         [](const auto& info) { return "F" + std::to_string(info.param); });

// ---------------------------------------------------------------------------------------------
// Closed meshes at random camera poses. With B back-facing and F front-facing fragments at a
// sample, a closed surface gives B - F = 1 where the ray starts inside the solid (its point on
// the near plane is inside) and 0 elsewhere: the near plane cuts the surface open along closed
// loops, and B - F is the winding number of those loops around the sample. Snapping moves the
// loops by less than a subpixel, so within that margin of a loop B - F may be 0 or 1; everywhere
// else it is exact. And the silhouette has no holes: a sample inside some visible (clipped)
// triangle, farther than the margin from the outline (contour edges and near-plane loops), is
// covered; one outside them all is not.

bool isClosed(const Mesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      ++directed[{mesh.indices[t + k], mesh.indices[t + (k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    const auto back = directed.find({e.second, e.first});
    if (n != 1 || back == directed.end() || back->second != 1) return false;
  }
  return !directed.empty();
}

struct Segment {
  glm::dvec2 a, b;
};

double segmentDistance(glm::dvec2 s, const Segment& g) {
  const glm::dvec2 ab = g.b - g.a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(glm::dot(s - g.a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(s - (g.a + t * ab));
}

class PoseReference {
 public:
  PoseReference(int width, int height, double margin)
      : w_(width), h_(height), margin_(margin), inUnion_(size_t(width) * height, 0),
        nearOutline_(size_t(width) * height, 0), nearCut_(size_t(width) * height, 0),
        parity_(size_t(width) * height, 0) {}

  glm::dvec2 project(const glm::dvec4& p) const {
    return {(p.x / p.w * 0.5 + 0.5) * w_, (0.5 - p.y / p.w * 0.5) * h_};
  }

  // Builds everything from the clip-space positions the pipeline sees.
  void build(const std::vector<glm::dvec4>& clip, const std::vector<uint32_t>& indices) {
    const size_t triangles = indices.size() / 3;
    std::vector<int> facing(triangles, 0);  // +1 clockwise on screen, -1 ccw, 0 invisible
    std::vector<bool> degenerate(triangles, false);
    auto nearDistance = [&](uint32_t i) { return clip[i].z + clip[i].w; };
    auto cutPoint = [&](uint32_t i, uint32_t j) {
      // Symmetric in (i, j), so both triangles of an edge get the same point.
      if (i > j) std::swap(i, j);
      const double di = nearDistance(i), dj = nearDistance(j);
      return project(clip[i] + (di / (di - dj)) * (clip[j] - clip[i]));
    };
    for (size_t t = 0; t < triangles; ++t) {
      std::vector<glm::dvec2> poly;
      std::vector<glm::dvec2> cut;
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = indices[3 * t + k], j = indices[3 * t + (k + 1) % 3];
        const double di = nearDistance(i), dj = nearDistance(j);
        if (di >= 0) poly.push_back(project(clip[i]));
        if ((di >= 0) != (dj >= 0)) {
          poly.push_back(cutPoint(i, j));
          cut.push_back(poly.back());
        }
      }
      if (poly.size() < 3) continue;
      if (cut.size() == 2) addOutline({cut[0], cut[1]}, true);
      double area = 0;
      for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
        area += a.x * b.y - b.x * a.y;
      }
      facing[t] = area > 0 ? 1 : -1;
      degenerate[t] = std::abs(area) < 1e-6;
      fillPolygon(poly);
    }
    // Contour edges: shared by a visible triangle of each facing, or touching a degenerate one.
    std::map<std::pair<uint32_t, uint32_t>, size_t> firstUse;
    for (size_t t = 0; t < triangles; ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = indices[3 * t + k], j = indices[3 * t + (k + 1) % 3];
        const auto key = std::make_pair(std::min(i, j), std::max(i, j));
        const auto other = firstUse.find(key);
        if (other == firstUse.end()) {
          firstUse[key] = t;
          continue;
        }
        const size_t u = other->second;
        const bool contour = facing[t] != 0 && facing[u] != 0 &&
                             (facing[t] != facing[u] || degenerate[t] || degenerate[u]);
        if (!contour) continue;
        const double di = nearDistance(i), dj = nearDistance(j);
        if (di < 0 && dj < 0) continue;
        const glm::dvec2 a = di >= 0 ? project(clip[i]) : cutPoint(i, j);
        const glm::dvec2 b = dj >= 0 ? project(clip[j]) : cutPoint(i, j);
        addOutline({a, b}, false);
      }
    // Parity of the near-plane loops around each sample: crossings of the row to its right.
    for (int y = 0; y < h_; ++y) {
      const double sy = y + 0.5;
      std::vector<double> xs;
      for (const Segment& s : cuts_)
        if ((s.a.y > sy) != (s.b.y > sy))
          xs.push_back(s.a.x + (sy - s.a.y) / (s.b.y - s.a.y) * (s.b.x - s.a.x));
      std::sort(xs.begin(), xs.end());
      for (int x = 0; x < w_; ++x) {
        const size_t right = size_t(xs.end() - std::upper_bound(xs.begin(), xs.end(), x + 0.5));
        parity_[size_t(y) * w_ + x] = right % 2;
      }
    }
  }

  bool inUnion(size_t i) const { return inUnion_[i]; }
  bool nearOutline(size_t i) const { return nearOutline_[i]; }
  bool nearCut(size_t i) const { return nearCut_[i]; }
  int parity(size_t i) const { return parity_[i]; }
  size_t cutSegments() const { return cuts_.size(); }

 private:
  void fillPolygon(const std::vector<glm::dvec2>& poly) {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const glm::dvec2 p : poly) {
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    }
    const int px0 = std::max(0, int(std::floor(std::max(x0, -1.0) - 0.5))),
              px1 = std::min(w_ - 1, int(std::ceil(std::min(x1, w_ + 1.0))));
    const int py0 = std::max(0, int(std::floor(std::max(y0, -1.0) - 0.5))),
              py1 = std::min(h_ - 1, int(std::ceil(std::min(y1, h_ + 1.0))));
    for (int y = py0; y <= py1; ++y)
      for (int x = px0; x <= px1; ++x) {
        const glm::dvec2 s(x + 0.5, y + 0.5);
        bool pos = true, neg = true;
        for (size_t k = 0; k < poly.size(); ++k) {
          const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
          const double e = (b.x - a.x) * (s.y - a.y) - (b.y - a.y) * (s.x - a.x);
          // A sample on a shared edge belongs to both neighbours here; only the outline decides.
          const double tolerance = 1e-9 * glm::length(b - a);
          pos &= e >= -tolerance;
          neg &= e <= tolerance;
        }
        if (pos || neg) inUnion_[size_t(y) * w_ + x] = 1;
      }
  }

  void addOutline(const Segment& s, bool isCut) {
    if (isCut) cuts_.push_back(s);
    const int x0 = std::max(0, int(std::floor(std::max(std::min(s.a.x, s.b.x), -2.0) - margin_ - 1)));
    const int x1 = std::min(w_ - 1, int(std::ceil(std::min(std::max(s.a.x, s.b.x), w_ + 2.0) + margin_)));
    const int y0 = std::max(0, int(std::floor(std::max(std::min(s.a.y, s.b.y), -2.0) - margin_ - 1)));
    const int y1 = std::min(h_ - 1, int(std::ceil(std::min(std::max(s.a.y, s.b.y), h_ + 2.0) + margin_)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if (segmentDistance({x + 0.5, y + 0.5}, s) <= margin_) {
          nearOutline_[size_t(y) * w_ + x] = 1;
          if (isCut) nearCut_[size_t(y) * w_ + x] = 1;
        }
  }

  int w_, h_;
  double margin_;
  std::vector<uint8_t> inUnion_, nearOutline_, nearCut_, parity_;
  std::vector<Segment> cuts_;
};

struct PoseTotals {
  int poses = 0, posesCut = 0;
  uint64_t decided = 0, insideSolid = 0, silhouette = 0;
};

void expectClosedMeshAtPose(const Mesh& mesh, const glm::mat4& viewProjection, FixedPointFormat f,
                            int width, int height, const std::string& what, PoseTotals& totals) {
  TransformVertexShader vs;
  vs.modelViewProjection = viewProjection;
  std::array<std::vector<uint32_t>, 2> counts;  // [0] front-facing, [1] back-facing
  for (int pass = 0; pass < 2; ++pass) {
    PipelineState state = countingState(width, height, f, PositionSpace::Clip);
    state.cullMode = pass == 0 ? CullMode::Back : CullMode::Front;
    PipelineStatistics stats;
    counts[pass] = drawCounts(state, mesh.vertices, mesh.indices, vs, stats);
  }
  std::vector<glm::dvec4> clip;
  clip.reserve(mesh.vertices.size());
  for (const MeshVertex& v : mesh.vertices) clip.push_back(glm::dvec4(vs(v).position));
  // Snapping moves a vertex by at most half a subpixel on each axis.
  PoseReference ref(width, height, std::ldexp(1.0, -f.fractionBits) + 1e-6);
  ref.build(clip, mesh.indices);

  int wrong = 0;
  for (size_t i = 0; i < counts[0].size(); ++i) {
    const int front = int(counts[0][i]), back = int(counts[1][i]);
    const int d = back - front;
    std::string problem;
    if (ref.nearCut(i)) {
      if (d != 0 && d != 1) problem = "back - front is not 0 or 1 near a near-plane loop";
    } else if (d != ref.parity(i)) {
      problem = "back - front = " + std::to_string(d) + ", the solid says " +
                std::to_string(ref.parity(i));
    }
    if (problem.empty() && !ref.nearOutline(i)) {
      ++totals.decided;
      if (ref.inUnion(i) && front + back == 0) problem = "a hole in the silhouette";
      if (!ref.inUnion(i) && front + back != 0) problem = "covered outside the silhouette";
    }
    totals.insideSolid += !ref.nearCut(i) && ref.parity(i) == 1;
    totals.silhouette += front + back > 0;
    if (!problem.empty() && ++wrong <= 3)
      ADD_FAILURE() << what << ": pixel (" << i % width << ", " << i / width << ") front " << front
                    << ", back " << back << ": " << problem;
  }
  EXPECT_EQ(wrong, 0) << what;
  ++totals.poses;
  totals.posesCut += ref.cutSegments() > 0;
}

TEST(WatertightScale, ClosedMeshesAtRandomPoses) {
  const std::filesystem::path dir(RASTER_SHARED_MESHES);
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  constexpr int W = 160, H = 120;
  const int posesPerMesh = 48 / kScale;
  std::vector<std::string> closed;
  for (const auto& file : files) {
    Mesh mesh;
    ASSERT_TRUE(loadObj(file.string(), mesh).isOk()) << file;
    if (!isClosed(mesh)) continue;
    closed.push_back(file.filename().string());
    const uint64_t seed = 0xc105ed00 + closed.size();
    std::cout << "[ seed ] " << seed << " " << closed.back() << "\n";
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::vec3 centre = 0.5f * (mesh.boundsMin() + mesh.boundsMax());
    float radius = 0;
    for (const MeshVertex& v : mesh.vertices) radius = std::max(radius, glm::length(v.position - centre));
    PoseTotals totals;
    for (int pose = 0; pose < posesPerMesh; ++pose) {
      // Half the poses outside the bounding sphere, half close to or inside the mesh, with the
      // near plane at a random distance: many cut through the surface.
      const glm::dvec3 dir = glm::normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
      const double distance = radius * (pose % 2 ? 1.3 + 1.5 * u(rng) : 0.2 + 0.9 * u(rng));
      const glm::vec3 eye = centre + glm::vec3(dir * distance);
      const glm::vec3 target = centre + radius * 0.3f * glm::vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
      const glm::vec3 up = std::abs(dir.y) > 0.9 ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      const float nearPlane = radius * float(0.02 + 0.5 * u(rng));
      const glm::mat4 vp =
          glm::perspective(glm::radians(float(40 + 40 * u(rng))), float(W) / H, nearPlane,
                           radius * 20.0f) *
          glm::lookAt(eye, target, up);
      const FixedPointFormat f = FixedPointFormat::withFractionBits(1 + pose % 8);
      expectClosedMeshAtPose(mesh, vp, f, W, H,
                             closed.back() + " pose " + std::to_string(pose) + " " + f.name(), totals);
      if (HasFailure()) return;
    }
    std::cout << closed.back() << ": " << totals.poses << " poses, " << totals.posesCut
              << " cut by the near plane, " << totals.decided << " samples decided, "
              << totals.insideSolid << " inside the solid, " << totals.silhouette
              << " in the silhouette\n";
    // Not vacuous: the near plane cuts many poses, and inside-the-solid samples are checked.
    EXPECT_GT(totals.posesCut, posesPerMesh / 8) << closed.back();
    EXPECT_GT(totals.insideSolid, uint64_t(posesPerMesh) * 100) << closed.back();
    EXPECT_GT(totals.decided, uint64_t(posesPerMesh) * W * H / 2) << closed.back();
  }
  // The closed 2-manifolds of ../shared/data/meshes/README.md.
  EXPECT_EQ(closed, (std::vector<std::string>{"armadillo.obj", "bunny.obj", "bunny_lowres.obj",
                                              "fandisk.obj"}));
}

}  // namespace
}  // namespace rast
