// The rasterizer against the ray-cast reference (reference/ray_caster.h): the same mesh, camera
// and image size through both, compared pixel by pixel on the id of the visible triangle.
//
// Why the two may differ at all, and by how much. The rasterizer snaps every window-space vertex
// to the nearest subpixel (1/2^F pixel, F = 4 in 24.4 and 8 in 16.8), rounding x and y
// separately, so a vertex moves by at most half a step on each axis: at most
// delta = 0.5 * sqrt(2) steps in all. Every point of a triangle is the same barycentric
// combination of its vertices, so the affine map A from the exact triangle T to the snapped T'
// moves every point of T by at most delta. Hence:
//   * a pixel centre p in T' but not in T lies within delta of T, so within delta of its edges;
//   * a pixel centre p in T but not in T' lies within delta of T's edges as well: if the disc of
//     radius r > delta around p were inside T, A would move its boundary circle by less than r,
//     so the image of the disc (a subset of T') would still wind around p and contain it.
// So coverage can differ only at pixel centres within delta of a projected (unsnapped) edge of
// the triangle concerned. If the ray caster shows triangle a at p and the rasterizer b, then
// either a lost p by snapping (p near an edge of a), or b gained it (p near an edge of b), or
// both cover p in both renderers and only their depth order differs: the rasterizer's depth of a
// triangle at p is its exact depth at a point at most delta away (A^-1(p), same barycentrics, z
// not snapped), so it is off by at most |grad z| * delta, and an order flip needs
// |z_a(p) - z_b(p)| <= (|grad z_a| + |grad z_b|) * delta (+ float rounding). That is where two
// surfaces cross or touch (the bunny stands 0.003 units into the ground plane). When one side is
// background, the other triangle is the one that must have an edge near p.
// Near-plane (and far-plane) clipping cuts a triangle along the line where its window depth is 0
// (or 1) and snaps the new vertices like any other: the clipped polygon is the union of a fan of
// snapped triangles sharing snapped vertices, a piecewise-affine image of the exact polygon that
// moves no point by more than delta, so the argument above holds for the polygon, whose edges
// are the triangle's edges and the clip segment (RayCaster::depthClipEdgeDistance). The ray
// caster needs no clipping: it counts hits between the near and far planes only. (Triangles with
// a vertex behind the eye, w <= 0, have no such projection; none occurs in these scenes, and a
// mismatch on one would count as unexplained.)
//
// Epsilons on top of that bound, both measured by the test:
//   * kWindowEpsilon (px): the rasterizer transforms vertices in float (vertex shader), the
//     reference in double. Float clip coordinates carry a relative error of a few 1e-7, which
//     is ~1e-4 px at most for window positions within ~1,000 px (measured: 6.9e-5 px for the
//     default scene, 9e-6 for the bunny). 1e-3 px is 10x that and a third of the 16.8 delta;
//     the test asserts the largest difference over the vertices in front of the camera is below.
//   * kDepthEpsilon: the same for window depth (~1e-7), plus the float plane evaluation and the
//     float depth buffer, each a few ulps of 1 (6e-8).
// Ties: pixel centres exactly on an edge are within the bound, so fill-rule decisions and the
// ray caster's inclusive edges need no extra allowance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/draw.h"
#include "reference/ray_caster.h"
#include "scene/scene.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/triangle_id.h"

namespace rast {
namespace {

using reference::RayCaster;
using reference::RayCastImage;

constexpr double kWindowEpsilon = 1e-3;  // px
constexpr double kDepthEpsilon = 1e-6;   // window depth units

struct Comparison {
  int pixels = 0;
  int mismatches = 0;        // ids differ
  int nearEdge = 0;          // ... explained by snapping an edge
  int nearClipEdge = 0;      // ... explained by snapping an edge made by near/far clipping
  int depthOrder = 0;        // ... explained by a depth-order flip where two surfaces meet
  int unexplained = 0;
  int rayCovered = 0, rasterCovered = 0;
  double maxWindowError = 0, maxDepthError = 0;  // float vertex transform vs double
  uint64_t clippedTriangles = 0;                 // the rasterizer's clip.clipped
  std::string firstUnexplained;
};

std::vector<int64_t> rasterIds(const Mesh& mesh, const Camera& camera, int width, int height,
                               FixedPointFormat format, PipelineStatistics& stats) {
  Scene scene;
  scene.camera = camera;
  scene.objects.push_back({mesh, glm::mat4(1.0f), glm::vec3(1.0f)});
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.format = format;
  Framebuffer fb(width, height);
  const Status s = renderScene(scene, fb, state, ShadingMode::TriangleId, stats);
  EXPECT_TRUE(s) << s.message();
  std::vector<int64_t> ids(size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) ids[fb.index(x, y)] = TriangleIdShader::decode(fb.color(x, y));
  return ids;
}

// `shiftX` moves the rasterizer's picture right by that many pixels before comparing: the
// control that shows the comparison catches a renderer that is off.
Comparison compare(const Mesh& mesh, const Camera& camera, int width, int height,
                   FixedPointFormat format, int shiftX = 0) {
  const RayCaster caster(mesh, camera, width, height);
  const RayCastImage ray = caster.render();
  PipelineStatistics stats;
  const std::vector<int64_t> raster = rasterIds(mesh, camera, width, height, format, stats);

  Comparison c;
  c.pixels = width * height;
  c.clippedTriangles = stats.clipClipped;

  // The float vertex path of the rasterizer (WorldNormalVertexShader, identity model, as
  // renderScene draws a flattened mesh) against the reference's double projection.
  PipelineState state;
  state.viewport = {0, 0, width, height};
  const ScreenMapping mapping = ScreenMapping::forState(state);
  const WorldNormalVertexShader vs{glm::mat4(1.0f),
                                   camera.viewProjection(float(width) / float(height))};
  for (const MeshVertex& v : mesh.vertices) {
    double w;
    const glm::dvec3 exact = caster.toWindow(glm::dvec3(v.position), &w);
    if (w <= 0) continue;
    const WindowPosition f = mapping.toWindow(vs(v).position);
    c.maxWindowError = std::max({c.maxWindowError, std::abs(f.x - exact.x), std::abs(f.y - exact.y)});
    c.maxDepthError = std::max(c.maxDepthError, std::abs(f.z - exact.z));
  }

  const double step = std::ldexp(1.0, -format.fractionBits);
  const double delta = 0.5 * std::sqrt(2.0) * step;
  const double reach = delta + kWindowEpsilon;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int64_t a = ray.id(x, y);
      const int sx = x - shiftX;
      const int64_t b = sx >= 0 && sx < width ? raster[size_t(y) * width + sx] : -1;
      c.rayCovered += a >= 0;
      c.rasterCovered += b >= 0;
      if (a == b) continue;
      ++c.mismatches;
      if ((a >= 0 && caster.edgeDistance(uint32_t(a), x, y) <= reach) ||
          (b >= 0 && caster.edgeDistance(uint32_t(b), x, y) <= reach)) {
        ++c.nearEdge;
        continue;
      }
      if ((a >= 0 && caster.depthClipEdgeDistance(uint32_t(a), x, y) <= reach) ||
          (b >= 0 && caster.depthClipEdgeDistance(uint32_t(b), x, y) <= reach)) {
        ++c.nearClipEdge;
        continue;
      }
      if (a >= 0 && b >= 0 && caster.hits(uint32_t(b), x, y)) {
        const double px = x + 0.5, py = y + 0.5;
        const double za = caster.windowDepth(uint32_t(a), px, py);
        const double zb = caster.windowDepth(uint32_t(b), px, py);
        const double slack =
            (glm::length(caster.depthGradient(uint32_t(a))) +
             glm::length(caster.depthGradient(uint32_t(b)))) * reach + 2 * kDepthEpsilon;
        if (std::abs(za - zb) <= slack) {
          ++c.depthOrder;
          continue;
        }
      }
      if (c.unexplained++ == 0) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "pixel (%d, %d): ray %lld, raster %lld, edge distances %.5f / %.5f px", x, y,
                      (long long)a, (long long)b,
                      a >= 0 ? caster.edgeDistance(uint32_t(a), x, y) : -1.0,
                      b >= 0 ? caster.edgeDistance(uint32_t(b), x, y) : -1.0);
        c.firstUnexplained = buf;
      }
    }
  return c;
}

void report(const char* what, FixedPointFormat format, const Comparison& c) {
  std::printf("[ray-cast vs %s %s] %d of %d pixels differ: %d near an edge, %d near a "
              "near-plane clip edge, %d depth order, %d unexplained; covered %d (ray) / %d "
              "(raster); %llu triangles clipped; vertex error %.2g px, depth %.2g\n",
              format.name().c_str(), what, c.mismatches, c.pixels, c.nearEdge, c.nearClipEdge,
              c.depthOrder, c.unexplained, c.rayCovered, c.rasterCovered,
              (unsigned long long)c.clippedTriangles, c.maxWindowError, c.maxDepthError);
}

Scene flattenedDefaultScene() {
  const Scene s = defaultScene();
  Scene flat = s;
  flat.objects.clear();
  flat.objects.push_back({flattenScene(s), glm::mat4(1.0f), glm::vec3(1.0f)});
  return flat;
}

Mesh sharedBunny() {
  Mesh mesh;
  const Status s = loadObj(RASTER_SHARED_MESHES "/bunny_lowres.obj", mesh);
  EXPECT_TRUE(s) << s.message();
  return mesh;
}

Comparison expectAgreement(const char* what, const Mesh& mesh, const Camera& camera,
                           FixedPointFormat format, double maxMismatchFraction) {
  const int width = 320, height = 240;
  const Comparison c = compare(mesh, camera, width, height, format);
  report(what, format, c);
  EXPECT_LT(c.maxWindowError, kWindowEpsilon);
  EXPECT_LT(c.maxDepthError, kDepthEpsilon);
  EXPECT_EQ(c.unexplained, 0) << c.firstUnexplained;
  EXPECT_LE(c.mismatches, maxMismatchFraction * c.pixels);
  return c;
}

// The mismatch budgets. Only pixel centres within delta of an edge can flip (0.044 px in 24.4,
// 0.0028 px in 16.8, 16x less), so the count scales with the projected edge length times delta:
// 105 (default scene) and 143 (bunny) pixels in 24.4, 10 and 9 in 16.8 when this was written.
// The budgets, 1 % (768 px) and 0.1 % (77 px) of the image, leave 5-8x headroom for other
// rounding, while a broad disagreement (the picture shifted by one pixel: ~6,700 mismatches, see
// ComparisonCatchesAShiftedPicture) fails them, as does any single unexplained pixel.
TEST(RayCaster, DefaultSceneMatchesRasterizer24_4) {
  const Scene flat = flattenedDefaultScene();
  expectAgreement("default scene", flat.objects[0].mesh, flat.camera, FixedPointFormat::d24_4(),
                  0.01);
}

TEST(RayCaster, DefaultSceneMatchesRasterizer16_8) {
  const Scene flat = flattenedDefaultScene();
  expectAgreement("default scene", flat.objects[0].mesh, flat.camera, FixedPointFormat::d16_8(),
                  0.001);
}

TEST(RayCaster, BunnyMatchesRasterizer24_4) {
  const Mesh bunny = sharedBunny();
  expectAgreement("bunny_lowres", bunny, frameMesh(bunny), FixedPointFormat::d24_4(), 0.01);
}

TEST(RayCaster, BunnyMatchesRasterizer16_8) {
  const Mesh bunny = sharedBunny();
  expectAgreement("bunny_lowres", bunny, frameMesh(bunny), FixedPointFormat::d16_8(), 0.001);
}

// The bunny from close up (the camera at 0.55 of frameMesh's distance): the near plane cuts
// through the ears and back, so the rasterizer clips (the ray caster just ignores hits before
// the near plane) and the edges clipping makes are checked too: when this was written, 10 of the
// 274 mismatched pixels in 24.4 lay near a clip edge only (none of the 16 in 16.8).
Camera closeUp(const Mesh& mesh) {
  Camera camera = frameMesh(mesh);
  camera.eye = camera.target + (camera.eye - camera.target) * 0.55f;
  return camera;
}

TEST(RayCaster, BunnyCloseUpNearPlaneClipping24_4) {
  const Mesh bunny = sharedBunny();
  const Comparison c = expectAgreement("bunny_lowres close-up", bunny, closeUp(bunny),
                                       FixedPointFormat::d24_4(), 0.01);
  EXPECT_GT(c.clippedTriangles, 100u);  // the case this test is for: 111 when written
}

TEST(RayCaster, BunnyCloseUpNearPlaneClipping16_8) {
  const Mesh bunny = sharedBunny();
  const Comparison c = expectAgreement("bunny_lowres close-up", bunny, closeUp(bunny),
                                       FixedPointFormat::d16_8(), 0.001);
  EXPECT_GT(c.clippedTriangles, 100u);
}

// The control: the same comparison against a rasterized picture one pixel off must fail loudly.
TEST(RayCaster, ComparisonCatchesAShiftedPicture) {
  const Mesh bunny = sharedBunny();
  const Comparison c = compare(bunny, frameMesh(bunny), 320, 240, FixedPointFormat::d24_4(), 1);
  report("bunny_lowres shifted 1 px", FixedPointFormat::d24_4(), c);
  EXPECT_GT(c.unexplained, 1000);
}

// render() (bounding boxes) agrees with the brute-force definition castPixel() everywhere it is
// sampled, ids and depth.
TEST(RayCaster, BoundingBoxesLoseNothing) {
  const Scene flat = flattenedDefaultScene();
  const RayCaster caster(flat.objects[0].mesh, flat.camera, 160, 120);
  const RayCastImage image = caster.render(true);
  int covered = 0;
  for (int y = 0; y < 120; y += 3)
    for (int x = 0; x < 160; x += 3) {
      const reference::RayHit hit = caster.castPixel(x, y);
      ASSERT_EQ(image.id(x, y), hit.triangle) << x << ", " << y;
      ASSERT_EQ(image.depth[size_t(y) * 160 + x], hit.depth) << x << ", " << y;
      covered += hit.triangle >= 0;
    }
  // Sky above the horizon, ground and objects below: both kinds are sampled.
  EXPECT_GT(covered, 100);
  EXPECT_LT(covered, 54 * 40 - 100);
}

// A hand case with numbers known in closed form. Camera at z = 5 looking down -z, 90 degrees
// vertical field of view, square image: the point (x, y, 0) has clip w = 5 and projects to
// window (50 + 10x, 50 - 10y) in a 100x100 image.
struct HandCase {
  Mesh mesh;
  Camera camera;
  HandCase() {
    camera.eye = {0, 0, 5};
    camera.target = {0, 0, 0};
    camera.fovYDegrees = 90.0f;
    camera.nearPlane = 1.0f;
    camera.farPlane = 10.0f;
    // Triangle 0 at z = 0: window (30, 70), (70, 70), (50, 30). Triangle 1 at z = 1 (clip
    // w = 4, so window (50 + 12.5x, 50 - 12.5y)): the same shape shifted right by 10 px,
    // (40, 70), (80, 70), (60, 30), and nearer.
    for (glm::vec3 p : {glm::vec3(-2, -2, 0), glm::vec3(2, -2, 0), glm::vec3(0, 2, 0),
                        glm::vec3(-0.8f, -1.6f, 1), glm::vec3(2.4f, -1.6f, 1),
                        glm::vec3(0.8f, 1.6f, 1)})
      mesh.vertices.push_back({p, {0, 0, 1}});
    mesh.indices = {0, 1, 2, 3, 4, 5};
  }
};

TEST(RayCaster, HandCaseProjectionAndEdgeDistance) {
  const HandCase h;
  const RayCaster caster(h.mesh, h.camera, 100, 100);
  // Float matrices (tan(45 deg) in float, lookAt) put the projection off by ~1e-5 px at most.
  const double eps = 1e-4;
  const auto& p = caster.projected(0);
  ASSERT_TRUE(p.inFront);
  EXPECT_NEAR(p.window[0].x, 30, eps);
  EXPECT_NEAR(p.window[0].y, 70, eps);
  EXPECT_NEAR(p.window[2].x, 50, eps);
  EXPECT_NEAR(p.window[2].y, 30, eps);
  // Window depth of z = 0 seen from distance d = 5: 0.5 * ndc + 0.5 with
  // ndc = (f + n) / (f - n) - 2 f n / ((f - n) d) = 11/9 - 20/45.
  const double depth0 = 0.5 * (11.0 / 9.0 - 20.0 / 45.0) + 0.5;
  EXPECT_NEAR(p.window[0].z, depth0, 1e-6);
  // Pixel (50, 69): centre (50.5, 69.5), half a pixel above the bottom edge y = 70.
  EXPECT_NEAR(caster.edgeDistance(0, 50, 69), 0.5, eps);
  // Pixel (50, 40): centre (50.5, 40.5); the right edge runs from (70, 70) to (50, 30), direction
  // (-1, -2)/sqrt(5), so the distance is |(50.5-70)*(-2) - (40.5-70)*(-1)| / sqrt(5).
  EXPECT_NEAR(caster.edgeDistance(0, 50, 40), std::abs(39.0 - 29.5) / std::sqrt(5.0), eps);
  // Distance to a segment, not its line: pixel (20, 69) is beyond vertex (30, 70).
  EXPECT_NEAR(caster.edgeDistance(0, 20, 69), std::hypot(9.5, 0.5), eps);
  // The plane z = 0 faces the camera: constant depth, zero gradient.
  EXPECT_NEAR(caster.windowDepth(0, 10, 10), depth0, 1e-6);
  EXPECT_NEAR(glm::length(caster.depthGradient(0)), 0.0, 1e-9);
}

TEST(RayCaster, HandCaseNearestTriangleWins) {
  const HandCase h;
  const RayCaster caster(h.mesh, h.camera, 100, 100);
  const RayCastImage image = caster.render(true);
  // Triangle 1 (nearer) spans window x 40..80 at the bottom; triangle 0 spans 30..70.
  EXPECT_EQ(image.id(35, 68), 0);   // only triangle 0
  EXPECT_EQ(image.id(50, 68), 1);   // both: triangle 1 is nearer
  EXPECT_EQ(image.id(75, 68), 1);   // only triangle 1
  EXPECT_EQ(image.id(50, 10), -1);  // above both apexes
  EXPECT_EQ(image.id(50, 71), -1);  // below both bases
  // Depth of z = 1 seen from distance 4: ndc = 11/9 - 20/36.
  EXPECT_NEAR(image.depth[68 * 100 + 50], 0.5 * (11.0 / 9.0 - 20.0 / 36.0) + 0.5, 1e-6);
  EXPECT_EQ(image.depth[10 * 100 + 50], 1.0);
  // Exact pixel counts. Both triangles are 40 px wide at the base and 40 px high, apex on top:
  // row y (30..69) covers the centres x + 0.5 within (y + 0.5 - 30) / 2 of the axis (50 or 60).
  // No centre lies on an edge: the half-widths are odd multiples of 1/4 px, the centres' offsets
  // from the axis even multiples (half-integers), so every centre is at least 1/4 px from an edge
  // horizontally and float rounding of the matrices (~1e-5 px) cannot change a count.
  int count0 = 0, count1 = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      count0 += caster.hits(0, x, y);
      count1 += caster.hits(1, x, y);
    }
  int expected = 0;
  for (int y = 30; y < 70; ++y)
    for (int x = 0; x < 100; ++x) expected += std::abs(x + 0.5 - 50) <= (y + 0.5 - 30) / 2;
  EXPECT_EQ(expected, 800);  // = the area, as it happens for this grid-aligned triangle
  EXPECT_EQ(count0, expected);
  EXPECT_EQ(count1, expected);
}

}  // namespace
}  // namespace rast
