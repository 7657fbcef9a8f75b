#include "scene/frame.h"

#include <memory>
#include <stdexcept>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/depth_visualizer.h"
#include "shaders_cpp/lambert.h"
#include "shaders_cpp/normal_visualizer.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/triangle_id.h"

namespace rast {
namespace {

// TriangleIdShader's encoding, counted across the draws of a frame.
struct FrameTriangleIdShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = false;
  uint32_t base = 0;

  PixelResult operator()(const Fragment<0>& f) const {
    const uint32_t id = base + f.primitiveId + 1;
    return {glm::vec4(float(id & 255), float((id >> 8) & 255), float((id >> 16) & 255), 255.0f) /
            255.0f};
  }
};

// Runs `call`'s vertices and shader, or the same vertices with the triangle-id shader.
template <class VS, class PS>
Status runPass(Framebuffer& fb, const PipelineState& state, std::span<const typename VS::Vertex> vertices,
               std::span<const uint32_t> indices, const VS& vs, const PS& ps, PixelPass pass,
               uint32_t idBase, PipelineStatistics& stats, const ExecutionOptions& exec) {
  if (pass == PixelPass::TriangleId) {
    const FrameTriangleIdShader ids{idBase};
    return draw(fb, state, DrawCall<VS, FrameTriangleIdShader>{vertices, indices, vs, ids}, stats, exec);
  }
  return draw(fb, state, DrawCall<VS, PS>{vertices, indices, vs, ps}, stats, exec);
}

FrameDraw meshDraw(const SceneDescription& scene, const DrawSpec& spec, const glm::mat4& viewProjection) {
  const Mesh& mesh = scene.meshes.at(spec.mesh).mesh;
  const WorldNormalVertexShader vs{spec.transform.matrix(), viewProjection};
  const ShaderSpec& s = spec.shader;
  FrameDraw d;
  d.label = spec.label;
  d.shader = shadingModeName(s.kind);
  d.state = spec.state;
  d.state.viewport = {0, 0, scene.width, scene.height};
  d.triangleCount = mesh.triangleCount();
  auto with = [&mesh, &d, vs](auto ps) {
    d.mayDiscard = decltype(ps)::kMayDiscard;
    return [&mesh, vs, ps](Framebuffer& fb, const PipelineState& state, PixelPass pass,
                           uint32_t idBase, PipelineStatistics& stats, const ExecutionOptions& exec) {
      return runPass(fb, state, std::span<const MeshVertex>(mesh.vertices),
                     std::span<const uint32_t>(mesh.indices), vs, ps, pass, idBase, stats, exec);
    };
  };
  switch (s.kind) {
    case ShadingMode::Lambert: {
      const PointLight& light = scene.lights.at(size_t(s.light));
      d.run = with(LambertShader{s.albedo, s.ambient, light.position, light.color});
      break;
    }
    case ShadingMode::Normals: d.run = with(NormalVisualizerShader{}); break;
    case ShadingMode::Depth: d.run = with(DepthVisualizerShader{s.depthNear, s.depthFar}); break;
    case ShadingMode::TriangleId: d.run = with(TriangleIdShader{}); break;
    case ShadingMode::Constant: d.run = with(ConstantColorShader{s.color}); break;
    case ShadingMode::BlinnPhong:
      // Needs a light pass first (scene/shadow_pass.h); frame plans hold single passes.
      throw std::invalid_argument("blinn-phong shading cannot be planned as one pass");
  }
  return d;
}

}  // namespace

FramePlan planFrame(const SceneDescription& scene, const Camera& camera) {
  FramePlan plan;
  plan.width = scene.width;
  plan.height = scene.height;
  plan.background = scene.background;
  plan.clearDepth = scene.resolvedClearDepth();
  const glm::mat4 viewProjection = camera.viewProjection(float(scene.width) / float(scene.height));
  for (const DrawSpec& spec : scene.draws) plan.draws.push_back(meshDraw(scene, spec, viewProjection));
  return plan;
}

FramePlan planTriangleList(const std::vector<WindowVertex>& vertices, const PipelineState& state,
                           ShadingMode shading, int width, int height) {
  FramePlan plan;
  plan.width = width;
  plan.height = height;
  const CompareOp op = state.depth.compare;
  plan.clearDepth = op == CompareOp::Greater || op == CompareOp::GreaterEqual ? 0.0f : 1.0f;
  FrameDraw d;
  d.label = "triangles";
  d.shader = shadingModeName(shading);
  d.state = state;
  d.state.positionSpace = PositionSpace::Window;
  d.triangleCount = vertices.size() / 3;
  auto indices = std::make_shared<std::vector<uint32_t>>(vertices.size());
  for (uint32_t i = 0; i < indices->size(); ++i) (*indices)[i] = i;
  auto with = [&vertices, &d, indices](auto ps) {
    d.mayDiscard = decltype(ps)::kMayDiscard;
    return [&vertices, indices, ps](Framebuffer& fb, const PipelineState& st, PixelPass pass,
                                    uint32_t idBase, PipelineStatistics& stats,
                                    const ExecutionOptions& exec) {
      const WindowSpaceVertexShader vs;
      return runPass(fb, st, std::span<const WindowVertex>(vertices),
                     std::span<const uint32_t>(*indices), vs, ps, pass, idBase, stats, exec);
    };
  };
  switch (shading) {
    case ShadingMode::TriangleId: d.run = with(TriangleIdShader{}); break;
    case ShadingMode::Depth: d.run = with(DepthVisualizerShader{}); break;
    default: d.run = with(ConstantColorShader{}); break;
  }
  plan.draws.push_back(std::move(d));
  return plan;
}

void FrameRecord::add(const FrameRecord& frame) {
  if (draws.empty()) {
    draws = frame.draws;
  } else {
    for (size_t i = 0; i < draws.size() && i < frame.draws.size(); ++i) {
      draws[i].stats += frame.draws[i].stats;
      draws[i].timings += frame.draws[i].timings;
    }
  }
  total += frame.total;
  timings += frame.timings;
  frames += frame.frames;
}

Status renderFrame(const FramePlan& plan, Framebuffer& fb, FrameRecord& record,
                   const ExecutionOptions& exec) {
  fb.clear(plan.background, plan.clearDepth);
  FrameRecord frame;
  frame.frames = 1;
  for (const FrameDraw& d : plan.draws) {
    DrawRecord r{d.label, d.state, d.mayDiscard, {}, {}};
    ExecutionOptions timed = exec;
    timed.timings = &r.timings;
    if (Status s = d.run(fb, d.state, PixelPass::Scene, 0, r.stats, timed); !s)
      return Status::error(d.label + ": " + s.message());
    frame.total += r.stats;
    frame.timings += r.timings;
    frame.draws.push_back(std::move(r));
  }
  record = std::move(frame);
  return Status::ok();
}

}  // namespace rast
