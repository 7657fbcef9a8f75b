#include "scene/shadow_pass.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/transform.h"

namespace rast {
namespace {

std::array<glm::vec3, 8> boxCorners(glm::vec3 lo, glm::vec3 hi) {
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
  return c;
}

// An up vector not parallel to `forward`.
glm::vec3 upFor(glm::vec3 forward) {
  return std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

}  // namespace

Status fitLightViewProjection(const Light& light, glm::vec3 boxMin, glm::vec3 boxMax,
                              glm::mat4& out) {
  const std::array<glm::vec3, 8> corners = boxCorners(boxMin, boxMax);
  const glm::vec3 centre = 0.5f * (boxMin + boxMax);
  const float radius = std::max(0.5f * glm::length(boxMax - boxMin), 1e-6f);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (light.kind == Light::Kind::Directional) {
    const glm::vec3 d = glm::normalize(light.direction);
    const glm::mat4 view = glm::lookAt(centre - 2.0f * radius * d, centre, upFor(d));
    glm::vec3 lo(kInf), hi(-kInf);
    for (const glm::vec3& c : corners) {
      const glm::vec3 v(view * glm::vec4(c, 1.0f));
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    // A margin of 1 % keeps the box's own faces off the near and far planes.
    const float pad = 0.01f * radius;
    out = glm::ortho(lo.x - pad, hi.x + pad, lo.y - pad, hi.y + pad, -hi.z - pad, -lo.z + pad) * view;
    return Status::ok();
  }
  glm::vec3 mean(0.0f);
  for (const glm::vec3& c : corners) {
    const glm::vec3 d = c - light.position;
    if (glm::length(d) > 0) mean += glm::normalize(d);
  }
  if (!(glm::length(mean) > 0))
    return Status::error("shadow map: the light is at the centre of the scene");
  const glm::vec3 forward = glm::normalize(mean);
  const glm::mat4 view = glm::lookAt(light.position, light.position + forward, upFor(forward));
  float nearZ = kInf, farZ = 0.0f, left = kInf, right = -kInf, bottom = kInf, top = -kInf;
  for (const glm::vec3& c : corners) {
    const glm::vec3 v(view * glm::vec4(c, 1.0f));
    const float depth = -v.z;
    if (!(depth > 1e-4f * radius))
      return Status::error(
          "shadow map: part of the scene is behind or beside the point light (one perspective "
          "map cannot cover it)");
    nearZ = std::min(nearZ, depth);
    farZ = std::max(farZ, depth);
    left = std::min(left, v.x / depth);
    right = std::max(right, v.x / depth);
    bottom = std::min(bottom, v.y / depth);
    top = std::max(top, v.y / depth);
  }
  const float n = 0.99f * nearZ, f = 1.01f * farZ;
  out = glm::frustum(left * n, right * n, bottom * n, top * n, n, f) * view;
  return Status::ok();
}

Light sceneLight(const Scene& scene) {
  Light light;
  light.kind = Light::Kind::Point;
  light.position = scene.lightPosition;
  return light;
}

void sceneBounds(const Scene& scene, glm::vec3& boxMin, glm::vec3& boxMax) {
  boxMin = glm::vec3(std::numeric_limits<float>::infinity());
  boxMax = -boxMin;
  for (const SceneObject& o : scene.objects)
    for (const MeshVertex& v : o.mesh.vertices) {
      const glm::vec3 p(o.model * glm::vec4(v.position, 1.0f));
      boxMin = glm::min(boxMin, p);
      boxMax = glm::max(boxMax, p);
    }
}

Status renderShadowMap(const Scene& scene, const glm::mat4& lightViewProjection,
                       Framebuffer& shadowMap, PipelineStatistics& stats,
                       const ExecutionOptions& exec) {
  PipelineState state;
  state.viewport = {0, 0, shadowMap.width(), shadowMap.height()};
  state.colorWrite = false;
  shadowMap.clear(glm::vec4(0.0f), 1.0f);
  const ConstantColorShader ps;  // never run: colour writes are off and it cannot discard
  for (const SceneObject& o : scene.objects) {
    const TransformVertexShader vs{lightViewProjection * o.model};
    const DrawCall<TransformVertexShader, ConstantColorShader> call{o.mesh.vertices,
                                                                    o.mesh.indices, vs, ps};
    if (Status s = draw(shadowMap, state, call, stats, exec); !s) return s;
  }
  return Status::ok();
}

Status renderSceneBlinnPhong(const Scene& scene, Framebuffer& fb, const PipelineState& state,
                             PipelineStatistics& stats, const ExecutionOptions& exec,
                             const ShadowSettings& shadows) {
  if (shadows.mapSize < 1 || shadows.mapSize > 16384)
    return Status::error("shadow map size " + std::to_string(shadows.mapSize) +
                         " is outside 1..16384");
  if (shadows.pcf != 1 && shadows.pcf != 3 && shadows.pcf != 5)
    return Status::error("shadow PCF size must be 1, 3 or 5");
  const Light light = sceneLight(scene);
  glm::vec3 lo, hi;
  sceneBounds(scene, lo, hi);
  glm::mat4 lightViewProjection;
  if (Status s = fitLightViewProjection(light, lo, hi, lightViewProjection); !s) return s;
  Framebuffer map(shadows.mapSize, shadows.mapSize);
  if (Status s = renderShadowMap(scene, lightViewProjection, map, stats, exec); !s) return s;

  const CompareOp op = state.depth.compare;
  const bool reversed = op == CompareOp::Greater || op == CompareOp::GreaterEqual;
  fb.clear(scene.background, reversed ? 0.0f : 1.0f);
  const float aspect = float(state.viewport.width) / float(state.viewport.height);
  const glm::mat4 viewProjection = scene.camera.viewProjection(aspect);
  for (const SceneObject& o : scene.objects) {
    const ShadowVertexShader vs{o.model, viewProjection, lightViewProjection,
                                shadows.normalOffset};
    BlinnPhongShader ps;
    ps.material.albedo = o.albedo;
    ps.light = light;
    ps.eye = scene.camera.eye;
    ps.shadowMap = ShadowMap::of(map);
    ps.depthBias = shadows.depthBias;
    ps.pcf = shadows.pcf;
    const DrawCall<ShadowVertexShader, BlinnPhongShader> call{o.mesh.vertices, o.mesh.indices,
                                                              vs, ps};
    if (Status s = draw(fb, state, call, stats, exec); !s) return s;
  }
  return Status::ok();
}

}  // namespace rast
