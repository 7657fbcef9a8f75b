// Scenes of meshes under one camera and one point light, and how to render them.
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "pipeline/execution.h"
#include "pipeline/framebuffer.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "scene/camera.h"
#include "scene/mesh.h"

namespace rast {

struct SceneObject {
  Mesh mesh;
  glm::mat4 model{1.0f};
  glm::vec3 albedo{0.8f};
};

struct Scene {
  std::vector<SceneObject> objects;
  Camera camera;
  glm::vec3 lightPosition{0.0f, 10.0f, 10.0f};
  glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
};

// What the pixel shader shows.
// BlinnPhong: shadow-mapped Blinn-Phong from the scene's point light (scene/shadow_pass.h).
enum class ShadingMode { Lambert, Normals, Depth, TriangleId, Constant, BlinnPhong };
bool parseShadingMode(const std::string& name, ShadingMode& out);

// The reference text's scene: a green triangle floating over a ground plane, lit by a point
// light, with the Stanford bunny (compiled into the binary) sitting on the plane.
Scene defaultScene();

// Every object transformed to world space and joined into one mesh, in object order: one draw
// whose primitive ids index the joined triangles (used by the ray-cast reference).
Mesh flattenScene(const Scene& scene);

// Clears `fb` (colour to the background, depth to `state`'s clear value: 1, or 0 for reversed
// compares) and draws every object, one draw each, with the camera over the state's viewport.
Status renderScene(const Scene& scene, Framebuffer& fb, const PipelineState& state,
                   ShadingMode shading, PipelineStatistics& stats,
                   const ExecutionOptions& exec = {});

}  // namespace rast
