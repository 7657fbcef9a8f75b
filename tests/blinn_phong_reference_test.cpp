// Shadow-mapped Blinn-Phong (scene/shadow_pass.h) against the ray-cast reference with shadow
// rays (reference/ray_caster.h), on the built-in default scene, 320x240, 24.4.
//
// Which pixels must agree, and how closely. Away from the edges of the visible triangle, the
// rasterizer's varyings at a pixel centre p are the exact varyings at a point p' within
// reach = delta + 1e-3 px of p (ray_caster_test.cpp: snapping moves each point of a triangle by at
// most delta = 0.044 px, and the float vertex transform adds < 1e-3 px). So the rasterized colour
// lies within the range of the exact shading over the disc of radius `reach` around p, plus
//   * 0.5/255: packColor rounds to the nearest of 256 levels;
//   * 2e-5: float evaluation of the shading (normalize, pow(., 32): ~32 * 6e-8 relative, and
//     a few ulps elsewhere), with room to spare.
// The range over the disc is estimated from the exact shading at 8 points on its rim: for a
// shading that is smooth at this scale (linear over 0.05 px), the largest change lies on the rim
// and 8 directions see at least cos(22.5 deg) = 0.92 of it; the factor 1.25 covers that and the
// curvature. Per pixel: tolerance = 1.25 * rimRange + 0.5/255 + 2e-5.
//
// Excluded: pixels within 1.5 px of an edge of their triangle or of a clip edge, pixels with a
// neighbour showing another triangle (silhouettes), pixels whose visible triangle differs between
// the two renderers (only possible within delta of an edge or where surfaces meet, checked by
// ray_caster_test.cpp), and pixels near a shadow boundary: those where the ideal shadow map (the
// ray-cast depth through every texel centre of the same light view, in double) does not give the
// shadow ray's answer, with a margin of 2e-5 in depth, on every texel within PCF radius + 2 of
// the lookup. On all remaining pixels the shadow map must agree with the shadow ray exactly.
//
// The shadow-map-versus-ray-traced difference over all pixels is reported as a count and written
// as an image (red: the map shadows a lit point; blue: the map lights a shadowed point).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pipeline/draw.h"
#include "reference/ray_caster.h"
#include "scene/shadow_pass.h"
#include "shaders_cpp/triangle_id.h"

#include <OpenImageIO/imageio.h>

namespace rast {
namespace {

using reference::RayCaster;
using reference::SurfacePoint;

constexpr int kWidth = 320, kHeight = 240;

struct Renders {
  std::vector<glm::vec4> color;   // Blinn-Phong, unpacked
  std::vector<uint32_t> visible;  // shadow visibility byte
  std::vector<int64_t> ids;       // flattened triangle ids
};

Renders rasterize(const Scene& scene, const ShadowSettings& settings, const glm::mat4& lightVP) {
  PipelineState state;
  state.viewport = {0, 0, kWidth, kHeight};
  PipelineStatistics stats;
  Renders r;
  Framebuffer fb(kWidth, kHeight);
  EXPECT_TRUE(renderSceneBlinnPhong(scene, fb, state, stats, {}, settings));
  for (PackedColor c : fb.colorPlane()) r.color.push_back(unpackColor(c));

  Framebuffer map(settings.mapSize, settings.mapSize);
  EXPECT_TRUE(renderShadowMap(scene, lightVP, map, stats));
  fb.clear(glm::vec4(0), 1.0f);
  const glm::mat4 viewProjection = scene.camera.viewProjection(float(kWidth) / kHeight);
  for (const SceneObject& o : scene.objects) {
    const ShadowVertexShader vs{o.model, viewProjection, lightVP, settings.normalOffset};
    const ShadowVisibilityShader ps{ShadowMap::of(map), settings.depthBias, settings.pcf};
    EXPECT_TRUE(draw(fb, state, DrawCall<ShadowVertexShader, ShadowVisibilityShader>{
                                    o.mesh.vertices, o.mesh.indices, vs, ps}, stats));
  }
  for (PackedColor c : fb.colorPlane()) r.visible.push_back(c & 255u);

  Scene flat = scene;
  flat.objects = {{flattenScene(scene), glm::mat4(1.0f), glm::vec3(1.0f)}};
  EXPECT_TRUE(renderScene(flat, fb, state, ShadingMode::TriangleId, stats));
  for (PackedColor c : fb.colorPlane()) r.ids.push_back(TriangleIdShader::decode(c));
  return r;
}

TEST(BlinnPhongReference, DefaultSceneMatchesRayTracedShadingAndShadows) {
  const Scene scene = defaultScene();
  ShadowSettings settings;
  settings.mapSize = 1024;
  settings.pcf = 1;
  const Light light = sceneLight(scene);
  glm::vec3 lo, hi;
  sceneBounds(scene, lo, hi);
  glm::mat4 lightVP;
  ASSERT_TRUE(fitLightViewProjection(light, lo, hi, lightVP));
  const Renders raster = rasterize(scene, settings, lightVP);

  const Mesh flat = flattenScene(scene);
  std::vector<BlinnPhongMaterial> materials;
  for (const SceneObject& o : scene.objects)
    materials.insert(materials.end(), o.mesh.triangleCount(), BlinnPhongMaterial{o.albedo});
  const RayCaster caster(flat, scene.camera, kWidth, kHeight);
  const reference::RayCastImage image = caster.render();
  const RayCaster lightCaster(flat, lightVP, settings.mapSize, settings.mapSize);
  const reference::RayCastImage idealMap = lightCaster.render(true);
  const glm::dvec3 eye(scene.camera.eye);

  const double reach = 0.5 * std::sqrt(2.0) / 16 + 1e-3;
  const int lookupRadius = settings.pcf / 2;
  std::vector<int64_t> firstTriangle;  // of each object in the flattened mesh
  for (int64_t t = 0; const SceneObject& o : scene.objects) {
    firstTriangle.push_back(t);
    t += int64_t(o.mesh.triangleCount());
  }
  auto objectOf = [&](int64_t triangle) {
    if (triangle < 0) return -1;
    return int(std::upper_bound(firstTriangle.begin(), firstTriangle.end(), triangle) -
               firstTriangle.begin()) - 1;
  };
  int covered = 0, clear = 0, shadowMismatch = 0, mapShadowsLit = 0, mapLightsShadowed = 0,
      clearShadowWrong = 0, shadingWrong = 0, truthShadowed = 0, shadowMismatchShown = 0;
  double worstExcess = -1;
  std::string firstWrong;
  std::vector<uint8_t> picture(size_t(kWidth) * kHeight * 3, 0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const size_t k = size_t(y) * kWidth + x;
      const int64_t id = image.id(x, y);
      if (id < 0) continue;
      ++covered;
      SurfacePoint sp;
      ASSERT_TRUE(caster.surfaceAt(uint32_t(id), x + 0.5, y + 0.5, sp));
      const bool lit = !caster.occluded(sp.position, light, id);
      truthShadowed += !lit;
      const bool sameTriangle = raster.ids[k] == id;
      const bool mapLit = raster.visible[k] == 255;
      glm::dvec3 nrm = glm::normalize(sp.normal);
      if (!sp.frontFacing) nrm = -nrm;
      const bool facesLight = glm::dot(nrm, glm::normalize(glm::dvec3(light.position) - sp.position)) > 0;
      if (sameTriangle && mapLit != lit) {
        ++shadowMismatch;
        shadowMismatchShown += facesLight;
        (mapLit ? mapLightsShadowed : mapShadowsLit) += 1;
      }
      uint8_t* rgb = &picture[3 * k];
      rgb[0] = rgb[1] = rgb[2] = lit ? 200 : 90;
      if (sameTriangle && mapLit != lit) {
        rgb[0] = mapLit ? 0 : 255;
        rgb[1] = 0;
        rgb[2] = mapLit ? 255 : 0;
      }

      // Exclusions (see the top of the file).
      if (!sameTriangle || caster.edgeDistance(uint32_t(id), x, y) <= 1.5 ||
          caster.depthClipEdgeDistance(uint32_t(id), x, y) <= 1.5)
        continue;
      bool silhouette = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < kWidth && ny < kHeight) silhouette |= image.id(nx, ny) != id;
        }
      if (silhouette) continue;
      const glm::dvec3 lookup = lightCaster.toWindow(sp.position + double(settings.normalOffset) * sp.normal);
      const int tx = int(std::floor(lookup.x)), ty = int(std::floor(lookup.y));
      const int n = settings.mapSize;
      auto objectAt = [&](int i, int j) {
        return i < 0 || j < 0 || i >= n || j >= n ? -1 : objectOf(idealMap.id(i, j));
      };
      bool agrees = true;
      for (int j = ty - lookupRadius; j <= ty + lookupRadius && agrees; ++j)
        for (int i = tx - lookupRadius; i <= tx + lookupRadius && agrees; ++i) {
          if (i < 0 || j < 0 || i >= n || j >= n) {
            agrees = lit;
            continue;
          }
          const double d = lookup.z - settings.depthBias - idealMap.depth[size_t(j) * n + i];
          agrees = lit ? d < -2e-5 : d > 2e-5;
          for (int b = -1; b <= 1; ++b)
            for (int a = -1; a <= 1; ++a) agrees &= objectAt(i + a, j + b) == objectAt(i, j);
        }
      if (!agrees) continue;
      ++clear;
      if (mapLit != lit && clearShadowWrong++ == 0)
        firstWrong = "shadow at (" + std::to_string(x) + ", " + std::to_string(y) + ")";

      const glm::dvec3 expected =
          RayCaster::shadeBlinnPhong(sp, materials[id], light, eye, lit ? 1.0 : 0.0);
      double rimRange = 0;
      for (int a = 0; a < 8; ++a) {
        const double angle = a * M_PI / 4;
        SurfacePoint q;
        ASSERT_TRUE(caster.surfaceAt(uint32_t(id), x + 0.5 + reach * std::cos(angle),
                                     y + 0.5 + reach * std::sin(angle), q));
        const glm::dvec3 c = RayCaster::shadeBlinnPhong(q, materials[id], light, eye, lit ? 1.0 : 0.0);
        for (int ch = 0; ch < 3; ++ch) rimRange = std::max(rimRange, std::abs(c[ch] - expected[ch]));
      }
      const double tolerance = 1.25 * rimRange + 0.5 / 255 + 2e-5;
      for (int ch = 0; ch < 3; ++ch) {
        // The rasterizer's colour is clamped to [0, 1] when packed; so is the expectation.
        const double e = std::clamp(expected[ch], 0.0, 1.0);
        const double excess = std::abs(double(raster.color[k][ch]) - e) - tolerance;
        worstExcess = std::max(worstExcess, excess);
        if (excess > 0 && shadingWrong++ == 0)
          firstWrong = "colour at (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                       std::to_string(ch) + ": " + std::to_string(raster.color[k][ch]) +
                       " vs " + std::to_string(e) + " +- " + std::to_string(tolerance);
      }
    }
  const std::string path = ::testing::TempDir() + "/shadow_map_vs_rays.png";
  auto out = OIIO::ImageOutput::create(path);
  if (out && out->open(path, OIIO::ImageSpec(kWidth, kHeight, 3, OIIO::TypeDesc::UINT8))) {
    (void)out->write_image(OIIO::TypeDesc::UINT8, picture.data());
    (void)out->close();
  }
  std::printf("[blinn-phong vs ray tracing] %d covered pixels, %d ray-traced in shadow; shadow map "
              "disagrees on %d (%.2f%%): %d shadowed but lit, %d lit but shadowed; %d (%.2f%%) "
              "where it shows (surface facing the light); %d pixels compared away from edges and "
              "shadow boundaries, worst colour error %.2g below its tolerance; picture: %s\n",
              covered, truthShadowed, shadowMismatch, 100.0 * shadowMismatch / covered,
              mapShadowsLit, mapLightsShadowed, shadowMismatchShown,
              100.0 * shadowMismatchShown / covered, clear, -worstExcess, path.c_str());
  EXPECT_EQ(clearShadowWrong, 0) << firstWrong;
  EXPECT_EQ(shadingWrong, 0) << firstWrong;
  // The comparison covers most of the picture, shadows included.
  EXPECT_GT(clear, covered * 3 / 4);
  EXPECT_GT(truthShadowed, 1000);
  // Shadow maps differ from shadow rays along shadow boundaries (about a texel wide), where the
  // biases let light through near contact (the bunny's feet) and at the bunny's terminator. When
  // written: 331 pixels (0.73 %), 207 of them on surfaces facing the light. The budget, 1.2 %,
  // fails with the earlier, smaller biases (2e-4 and 0.02: 1.62 %, acne on the bunny) and with
  // a map a few texels off; the shading comparison above is unaffected by either.
  EXPECT_LT(shadowMismatch, covered * 12 / 1000);
}

}  // namespace
}  // namespace rast
