// Shadow maps (pipeline/shadow_map.h, scene/shadow_pass.h): the lookup on a hand-made depth
// plane, and a scene whose shadow is known in closed form: a square occluder above a plane under
// a directional light casts an exact parallelogram, so every pixel farther from its border than
// the lookup can reach is exactly lit or exactly shadowed.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "pipeline/draw.h"
#include "scene/shadow_pass.h"
#include "shaders_cpp/blinn_phong.h"

namespace rast {
namespace {

// A 4x4 map: depth 0.5 everywhere but texel (1, 2), an occluder at depth 0.25.
struct HandMap {
  std::vector<float> depth = std::vector<float>(16, 0.5f);
  HandMap() { depth[2 * 4 + 1] = 0.25f; }
  ShadowMap view() const { return {depth.data(), 4, 4}; }
};

// The clip position (w = 2) whose window position is (x, y) and depth z in a 4x4 map.
glm::vec4 clipAt(float x, float y, float z) {
  const float w = 2.0f;
  return {(x / 4.0f * 2.0f - 1.0f) * w, (1.0f - y / 4.0f * 2.0f) * w, (2.0f * z - 1.0f) * w, w};
}

TEST(ShadowMapLookup, TexelBiasAndPcf) {
  const HandMap m;
  const ShadowMap map = m.view();
  // The occluded texel's area, just inside its corners: shadowed at depth 0.4, lit at 0.2.
  for (glm::vec2 p : {glm::vec2(1.01f, 2.01f), glm::vec2(1.99f, 2.99f), glm::vec2(1.5f, 2.5f)}) {
    EXPECT_EQ(map.visibility(clipAt(p.x, p.y, 0.4f), 0.0f), 0.0f) << p.x << ", " << p.y;
    EXPECT_EQ(map.visibility(clipAt(p.x, p.y, 0.2f), 0.0f), 1.0f);
  }
  EXPECT_EQ(map.visibility(clipAt(0.99f, 2.5f, 0.4f), 0.0f), 1.0f);  // the neighbour
  EXPECT_EQ(map.visibility(clipAt(1.5f, 3.01f, 0.4f), 0.0f), 1.0f);
  // Depth equal to the stored value is lit (the light pass's Less keeps the nearest); the bias
  // moves the comparison by exactly its value.
  EXPECT_EQ(map.visibility(clipAt(1.5f, 2.5f, 0.25f), 0.0f), 1.0f);
  EXPECT_EQ(map.visibility(clipAt(1.5f, 2.5f, 0.375f), 0.125f), 1.0f);
  EXPECT_EQ(map.visibility(clipAt(1.5f, 2.5f, 0.375f), 0.0625f), 0.0f);
  // PCF: the occluded texel is one of 9 (3x3) or 25 (5x5) around any texel next to it.
  EXPECT_EQ(map.visibility(clipAt(2.5f, 1.5f, 0.4f), 0.0f, 3), 8.0f / 9.0f);
  EXPECT_EQ(map.visibility(clipAt(1.5f, 2.5f, 0.4f), 0.0f, 3), 8.0f / 9.0f);
  EXPECT_EQ(map.visibility(clipAt(3.5f, 3.5f, 0.4f), 0.0f, 3), 1.0f);  // two texels away
  EXPECT_EQ(map.visibility(clipAt(3.5f, 0.5f, 0.4f), 0.0f, 5), 24.0f / 25.0f);
  // Texels beyond the map count as lit; so do points off the map, behind the light or NaN.
  EXPECT_EQ(map.visibility(clipAt(0.5f, 2.5f, 0.4f), 0.0f, 5), 24.0f / 25.0f);
  EXPECT_EQ(map.visibility(clipAt(-3.0f, 2.5f, 0.9f), 0.0f), 1.0f);
  EXPECT_EQ(map.visibility(glm::vec4(0, 0, 0, -1), 0.0f), 1.0f);
  EXPECT_EQ(map.visibility(glm::vec4(NAN, 0, 0, 1), 0.0f), 1.0f);
  EXPECT_EQ(map.visibility(glm::vec4(1e30f, 0, 0, 1e-30f), 0.0f, 5), 1.0f);
}

// ---- The analytic scene ----

Mesh quadY(float y, float x0, float x1, float z0, float z1) {
  Mesh m;
  for (glm::vec3 p : {glm::vec3(x0, y, z0), glm::vec3(x0, y, z1), glm::vec3(x1, y, z1),
                      glm::vec3(x1, y, z0)})
    m.vertices.push_back({p, {0, 1, 0}});
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

double segmentDistance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 ab = b - a;
  const double s = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(p - (a + s * ab));
}

struct AnalyticResult {
  int lit = 0, shadowed = 0, band = 0, bandPartial = 0, wrong = 0;
  std::string firstWrong;
};

// Plane y = 0 (±20), square occluder y = 2 (±2), light travelling along (1, -2, 0.5): the
// shadow is the square moved by (1, 0.5). The camera looks straight down; the camera pass draws
// the plane only (the occluder still casts its shadow through the light pass), so the whole
// shadow is in view. Each pixel's plane point is projected into the light's window in double and
// its distance to the occluder's projected outline measured in texels: the lookup reads texels
// whose centres lie within (r + 1/2) texels of it on each axis (r = pcf / 2), and a texel centre
// within 1/32 texel of the outline may be covered either way after snapping, so beyond
// (r + 1/2) * sqrt(2) + 0.1 texels the answer is exact.
AnalyticResult analyticShadow(int pcf) {
  const int mapSize = 512, size = 256;
  Scene scene;
  scene.objects.push_back({quadY(0, -20, 20, -20, 20), glm::mat4(1.0f), glm::vec3(0.8f)});
  scene.objects.push_back({quadY(2, -2, 2, -2, 2), glm::mat4(1.0f), glm::vec3(0.8f)});
  Light light;
  light.kind = Light::Kind::Directional;
  light.direction = glm::normalize(glm::vec3(1, -2, 0.5f));
  glm::vec3 lo, hi;
  sceneBounds(scene, lo, hi);
  glm::mat4 lightVP;
  EXPECT_TRUE(fitLightViewProjection(light, lo, hi, lightVP));
  Framebuffer map(mapSize, mapSize);
  PipelineStatistics stats;
  EXPECT_TRUE(renderShadowMap(scene, lightVP, map, stats));

  Camera camera;
  camera.eye = {0.5f, 25, 0.5f};
  camera.target = {0.5f, 0, 0.5f};
  camera.up = {0, 0, -1};
  camera.nearPlane = 1;
  camera.farPlane = 50;
  const glm::mat4 viewProjection = camera.viewProjection(1.0f);
  PipelineState state;
  state.viewport = {0, 0, size, size};
  Framebuffer fb(size, size);
  fb.clear(glm::vec4(1, 0, 0, 1), 1.0f);
  const ShadowVertexShader vs{glm::mat4(1.0f), viewProjection, lightVP, 0.0f};
  // The receiver's depth changes by ~1.6e-3 per texel along its steepest direction in the light
  // view, and the lookup compares against texel centres up to (r + 1/2) texels away on each
  // axis: bias 3e-3 * (r + 1/2) exceeds sqrt(2) * 1.6e-3 * (r + 1/2) and stays far below the
  // occluder's height above the plane (0.076 in depth).
  const ShadowVisibilityShader ps{ShadowMap::of(map), 3e-3f * (pcf / 2 + 0.5f), pcf};
  EXPECT_TRUE(draw(fb, state,
                   DrawCall<ShadowVertexShader, ShadowVisibilityShader>{
                       scene.objects[0].mesh.vertices, scene.objects[0].mesh.indices, vs, ps},
                   stats));

  const glm::dmat4 light64(lightVP), inverse = glm::inverse(glm::dmat4(viewProjection));
  auto lightWindow = [&](glm::dvec3 p) {
    const glm::dvec4 c = light64 * glm::dvec4(p, 1.0);
    return glm::dvec2((c.x / c.w * 0.5 + 0.5) * mapSize, (-c.y / c.w * 0.5 + 0.5) * mapSize);
  };
  glm::dvec2 outline[4];
  for (int k = 0; k < 4; ++k) outline[k] = lightWindow(glm::dvec3(scene.objects[1].mesh.vertices[k].position));
  const double reach = (pcf / 2 + 0.5) * std::sqrt(2.0) + 0.1;

  AnalyticResult r;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double nx = (x + 0.5) / (0.5 * size) - 1, ny = 1 - (y + 0.5) / (0.5 * size);
      const glm::dvec4 a = inverse * glm::dvec4(nx, ny, -1, 1), b = inverse * glm::dvec4(nx, ny, 1, 1);
      const glm::dvec3 p = glm::dvec3(a) / a.w, q = glm::dvec3(b) / b.w;
      const glm::dvec3 ground = p + (q - p) * (p.y / (p.y - q.y));
      const glm::dvec2 uv = lightWindow(ground);
      double distance = 1e300;
      int sides = 0;  // the outline is convex: inside iff on the same side of all four edges
      for (int k = 0; k < 4; ++k) {
        const glm::dvec2 e = outline[(k + 1) % 4] - outline[k], d = uv - outline[k];
        sides += e.x * d.y - e.y * d.x > 0 ? 1 : -1;
        distance = std::min(distance, segmentDistance(uv, outline[k], outline[(k + 1) % 4]));
      }
      const bool inside = std::abs(sides) == 4;
      const uint32_t red = fb.color(x, y) & 255u;
      if (distance <= reach) {
        ++r.band;
        r.bandPartial += red != 0 && red != 255;
        continue;
      }
      const uint32_t expected = inside ? 0u : 255u;
      (inside ? r.shadowed : r.lit) += 1;
      if (red != expected && r.wrong++ == 0)
        r.firstWrong = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): " +
                       std::to_string(red) + ", expected " + std::to_string(expected) +
                       ", distance " + std::to_string(distance) + " texels";
    }
  return r;
}

TEST(ShadowMapScene, SquareOccluderCastsAnExactSquare) {
  for (int pcf : {1, 3, 5}) {
    const AnalyticResult r = analyticShadow(pcf);
    std::printf("[square shadow, PCF %dx%d] %d lit, %d shadowed, %d in the border band (%d partly lit)\n",
                pcf, pcf, r.lit, r.shadowed, r.band, r.bandPartial);
    EXPECT_EQ(r.wrong, 0) << "PCF " << pcf << ": " << r.firstWrong;
    // The shadow (4 x 4 units, ~50 px per side) and the lit plane are both well sampled.
    EXPECT_GT(r.shadowed, 1500) << pcf;
    EXPECT_GT(r.lit, 40000) << pcf;
    if (pcf > 1) EXPECT_GT(r.bandPartial, 100) << pcf;  // filtering gives partial values
    else EXPECT_EQ(r.bandPartial, 0);
  }
}

// Without the bias the receiver compares against its own depth at texel centres and shadows
// itself on about half its pixels: the control that shows the bias is doing its work.
TEST(ShadowMapScene, NoBiasGivesAcne) {
  Scene scene;
  scene.objects.push_back({quadY(0, -20, 20, -20, 20), glm::mat4(1.0f), glm::vec3(0.8f)});
  Light light;
  light.kind = Light::Kind::Directional;
  light.direction = glm::normalize(glm::vec3(1, -2, 0.5f));
  glm::vec3 lo, hi;
  sceneBounds(scene, lo, hi);
  hi.y += 2;  // the same box as the analytic scene
  glm::mat4 lightVP;
  ASSERT_TRUE(fitLightViewProjection(light, lo, hi, lightVP));
  Framebuffer map(512, 512);
  PipelineStatistics stats;
  ASSERT_TRUE(renderShadowMap(scene, lightVP, map, stats));
  Camera camera;
  camera.eye = {0.5f, 25, 0.5f};
  camera.target = {0.5f, 0, 0.5f};
  camera.up = {0, 0, -1};
  PipelineState state;
  state.viewport = {0, 0, 128, 128};
  for (float bias : {0.0f, 2e-3f}) {
    Framebuffer fb(128, 128);
    fb.clear(glm::vec4(0), 1.0f);
    const ShadowVertexShader vs{glm::mat4(1.0f), camera.viewProjection(1.0f), lightVP, 0.0f};
    const ShadowVisibilityShader ps{ShadowMap::of(map), bias, 1};
    ASSERT_TRUE(draw(fb, state, DrawCall<ShadowVertexShader, ShadowVisibilityShader>{
                                    scene.objects[0].mesh.vertices, scene.objects[0].mesh.indices, vs, ps},
                     stats));
    int dark = 0;
    for (PackedColor c : fb.colorPlane()) dark += (c & 255u) == 0;
    if (bias == 0.0f) EXPECT_GT(dark, 128 * 128 / 10);
    else EXPECT_EQ(dark, 0);
  }
}

TEST(ShadowMapScene, LightFitErrors) {
  Light inside;
  inside.position = {0.3f, 1, 0.2f};
  glm::mat4 vp;
  const Status s = fitLightViewProjection(inside, {-1, 0, -1}, {1, 2, 1}, vp);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("behind or beside"), std::string::npos) << s.message();
  // A point light above the box: every corner projects inside the frustum.
  Light above;
  above.position = {3, 10, -2};
  ASSERT_TRUE(fitLightViewProjection(above, {-5, 0, -5}, {5, 2, 5}, vp));
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 c = vp * glm::vec4((i & 1) ? 5 : -5, (i & 2) ? 2 : 0, (i & 4) ? 5 : -5, 1);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(c[k] / c.w), 1.0f + 1e-5f) << i << " " << k;
    }
  }
}

}  // namespace
}  // namespace rast
