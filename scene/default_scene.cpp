#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/draw.h"
#include "scene/scene.h"
#include "scene/shadow_pass.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/depth_visualizer.h"
#include "shaders_cpp/lambert.h"
#include "shaders_cpp/normal_visualizer.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/triangle_id.h"

namespace rast {
namespace {

Mesh quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  Mesh m;
  for (glm::vec3 p : {a, b, c, d}) m.vertices.push_back({p, {0, 0, 1}});
  m.indices = {0, 1, 2, 0, 2, 3};
  computeVertexNormals(m);
  return m;
}

Mesh triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  Mesh m;
  for (glm::vec3 p : {a, b, c}) m.vertices.push_back({p, {0, 0, 1}});
  m.indices = {0, 1, 2};
  computeVertexNormals(m);
  return m;
}

template <class PS>
Status drawObject(Framebuffer& fb, const PipelineState& state, const SceneObject& object,
                  const glm::mat4& viewProjection, const PS& shader, PipelineStatistics& stats,
                  const ExecutionOptions& exec) {
  WorldNormalVertexShader vs{object.model, viewProjection};
  const DrawCall<WorldNormalVertexShader, PS> call{object.mesh.vertices, object.mesh.indices, vs,
                                                   shader};
  return draw(fb, state, call, stats, exec);
}

}  // namespace

bool parseShadingMode(const std::string& name, ShadingMode& out) {
  if (name == "lambert") out = ShadingMode::Lambert;
  else if (name == "normals") out = ShadingMode::Normals;
  else if (name == "depth") out = ShadingMode::Depth;
  else if (name == "triangle-id") out = ShadingMode::TriangleId;
  else if (name == "constant") out = ShadingMode::Constant;
  else if (name == "blinn-phong") out = ShadingMode::BlinnPhong;
  else return false;
  return true;
}

Scene defaultScene() {
  Scene s;
  // Counter-clockwise seen from above (+y), so the plane faces up.
  s.objects.push_back({quad({-24, 0, -24}, {-24, 0, 24}, {24, 0, 24}, {24, 0, -24}),
                       glm::mat4(1.0f), {0.75f, 0.75f, 0.72f}});
  s.objects.push_back({triangle({-15, 3, 2}, {-5, 3, -1}, {-9.5f, 11, -3}), glm::mat4(1.0f),
                       {0.15f, 0.8f, 0.2f}});
  s.objects.push_back({embeddedBunny(), glm::translate(glm::mat4(1.0f), {4, 0, 0}),
                       {0.85f, 0.8f, 0.7f}});
  s.camera.eye = {0, 13, 30};
  s.camera.target = {0, 4, 0};
  s.camera.nearPlane = 1.0f;
  s.camera.farPlane = 100.0f;
  s.lightPosition = {8, 24, 16};
  s.background = {0.55f, 0.7f, 0.9f, 1.0f};
  return s;
}

Mesh flattenScene(const Scene& scene) {
  Mesh out;
  for (const SceneObject& o : scene.objects) {
    const uint32_t base = uint32_t(out.vertices.size());
    for (const MeshVertex& v : o.mesh.vertices)
      out.vertices.push_back({glm::vec3(o.model * glm::vec4(v.position, 1.0f)),
                              glm::vec3(o.model * glm::vec4(v.normal, 0.0f))});
    for (uint32_t i : o.mesh.indices) out.indices.push_back(base + i);
  }
  return out;
}

Status renderScene(const Scene& scene, Framebuffer& fb, const PipelineState& state,
                   ShadingMode shading, PipelineStatistics& stats, const ExecutionOptions& exec) {
  if (shading == ShadingMode::BlinnPhong) return renderSceneBlinnPhong(scene, fb, state, stats, exec);
  const CompareOp op = state.depth.compare;
  const bool reversed = op == CompareOp::Greater || op == CompareOp::GreaterEqual;
  fb.clear(shading == ShadingMode::TriangleId ? glm::vec4(0, 0, 0, 1) : scene.background,
           reversed ? 0.0f : 1.0f);
  const float aspect = float(state.viewport.width) / float(state.viewport.height);
  const glm::mat4 viewProjection = scene.camera.viewProjection(aspect);
  for (const SceneObject& object : scene.objects) {
    Status s = Status::ok();
    switch (shading) {
      case ShadingMode::Lambert:
        s = drawObject(fb, state, object, viewProjection,
                       LambertShader{object.albedo, glm::vec3(0.08f), scene.lightPosition,
                                     glm::vec3(1.0f)},
                       stats, exec);
        break;
      case ShadingMode::Normals:
        s = drawObject(fb, state, object, viewProjection, NormalVisualizerShader{}, stats, exec);
        break;
      case ShadingMode::Depth:
        s = drawObject(fb, state, object, viewProjection, DepthVisualizerShader{0.9f, 1.0f}, stats, exec);
        break;
      case ShadingMode::TriangleId:
        s = drawObject(fb, state, object, viewProjection, TriangleIdShader{}, stats, exec);
        break;
      case ShadingMode::Constant:
        s = drawObject(fb, state, object, viewProjection,
                       ConstantColorShader{glm::vec4(object.albedo, 1.0f)}, stats, exec);
        break;
      case ShadingMode::BlinnPhong:  // drawn by renderSceneBlinnPhong, above
        break;
    }
    if (!s) return s;
  }
  return Status::ok();
}

}  // namespace rast
