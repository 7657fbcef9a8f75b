// A frame as a list of re-runnable draws. The renderer runs it once; the debugging passes
// (debug/) run the same draws again with a changed state or a triangle-id shader, through the
// real pipeline.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "pipeline/execution.h"
#include "pipeline/framebuffer.h"
#include "pipeline/instrumentation.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "shaders_cpp/window_space.h"

namespace rast {

// Which pixel shader a draw runs: its own, or one writing a frame-wide triangle id
// (idBase + primitiveId + 1, decoded by TriangleIdShader::decode).
enum class PixelPass { Scene, TriangleId };

struct FrameDraw {
  std::string label;
  std::string shader;       // the pixel shader's name
  PipelineState state;      // viewport included
  bool mayDiscard = false;  // whether its pixel shader can discard
  size_t triangleCount = 0;
  std::function<Status(Framebuffer&, const PipelineState&, PixelPass, uint32_t idBase,
                       PipelineStatistics&, const ExecutionOptions&)>
      run;
};

// Draws keep references to the meshes or vertices they were planned from.
struct FramePlan {
  int width = 0, height = 0;
  glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
  float clearDepth = 1.0f;
  std::vector<FrameDraw> draws;
};

// The scene's draws seen by `camera`.
FramePlan planFrame(const SceneDescription& scene, const Camera& camera);
// One draw of window-space triangles (constant, triangle-id or depth shading).
FramePlan planTriangleList(const std::vector<WindowVertex>& vertices, const PipelineState& state,
                           ShadingMode shading, int width, int height);

struct DrawRecord {
  std::string label;
  PipelineState state;
  bool mayDiscard = false;
  PipelineStatistics stats;
  StageTimings timings;
};

// Statistics and stage times per draw and for the frame (or, added up, a sequence of frames).
struct FrameRecord {
  std::vector<DrawRecord> draws;
  PipelineStatistics total;
  StageTimings timings;
  int frames = 0;

  // Adds another frame of the same plan, draw by draw.
  void add(const FrameRecord& frame);
};

// Clears `fb` to the plan's background and clear depth and runs every draw.
Status renderFrame(const FramePlan& plan, Framebuffer& fb, FrameRecord& record,
                   const ExecutionOptions& exec = {});

}  // namespace rast
