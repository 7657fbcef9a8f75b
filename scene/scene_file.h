// Scene files: a JSON description of an experiment (cameras, lights, meshes with transforms, and
// per draw the pipeline state and the shader with its parameters), read and written without
// recompiling anything. The schema is documented in README.md ("Scene files").
//
// Errors name the file, the JSON pointer of the offending value and what was expected:
//   scenes/x.json: /draws/1/state/cull: expected one of "none", "back", "front"
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "pipeline/state.h"
#include "pipeline/status.h"
#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "scene/scene.h"

namespace rast {

struct PointLight {
  glm::vec3 position{0.0f, 10.0f, 10.0f};
  glm::vec3 color{1.0f};
  friend bool operator==(const PointLight&, const PointLight&) = default;
};

// Where a mesh comes from. File paths are kept as written (relative to the scene file).
struct MeshSource {
  enum class Kind { File, Builtin, Inline };
  Kind kind = Kind::Inline;
  std::string path;                 // File: as written; Builtin: the name after "builtin:"
  std::vector<glm::vec3> positions;  // Inline
  std::vector<uint32_t> indices;     // Inline, three per triangle
  friend bool operator==(const MeshSource&, const MeshSource&) = default;
};

struct NamedMesh {
  std::string name;
  MeshSource source;
  Mesh mesh;  // loaded from the source
};

// Translation * rotation * scale, each left out of the product when it is the identity; or a
// matrix given whole.
struct Transform {
  glm::vec3 translate{0.0f};
  glm::vec3 rotateAxis{0.0f, 1.0f, 0.0f};
  float rotateDegrees = 0.0f;
  glm::vec3 scale{1.0f};
  std::optional<glm::mat4> explicitMatrix;
  glm::mat4 matrix() const;
  friend bool operator==(const Transform&, const Transform&) = default;
};

// A pixel shader by name with its parameters; only the kind's own parameters are read or written.
struct ShaderSpec {
  ShadingMode kind = ShadingMode::Lambert;
  glm::vec3 albedo{0.8f};        // lambert
  glm::vec3 ambient{0.08f};      // lambert
  int light = 0;                 // lambert: index into the scene's lights
  glm::vec4 color{1.0f};         // constant
  float depthNear = 0.0f;        // depth: the window depth shown white
  float depthFar = 1.0f;         // depth: the window depth shown black
  friend bool operator==(const ShaderSpec&, const ShaderSpec&) = default;
};

struct DrawSpec {
  std::string label;  // defaults to the mesh name
  size_t mesh = 0;    // index into SceneDescription::meshes
  Transform transform;
  PipelineState state;  // the viewport is the image's, set when the frame is drawn
  ShaderSpec shader;
};

struct SceneDescription {
  std::string description;
  int width = 960, height = 540;
  int samples = 1;  // per pixel: 1, or 4 or 8 for MSAA (the framebuffer's)
  glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
  std::optional<float> clearDepth;  // unset: 1, or 0 when the first draw compares greater
  Camera camera;
  std::vector<PointLight> lights;
  std::vector<NamedMesh> meshes;
  std::vector<DrawSpec> draws;
  std::optional<CameraAnimation> animation;
  std::string directory;  // where relative mesh paths start (the scene file's folder)

  float resolvedClearDepth() const;
};

// Everything but the loaded meshes (they follow from their sources).
bool sameDescription(const SceneDescription& a, const SceneDescription& b);

// Parses scene JSON; `name` stands for the file in messages and its folder anchors mesh paths.
Status parseSceneFile(const std::string& text, const std::string& name, SceneDescription& out);
Status loadSceneFile(const std::string& path, SceneDescription& out);
// The description as scene JSON (every field written out), which parses back to an equal one.
std::string sceneToJson(const SceneDescription& scene);

// A built-in scene rendered the way renderScene does: every object one draw with `state` and
// `shading`'s shader at renderScene's parameters (its meshes inline).
SceneDescription describeScene(const Scene& scene, const PipelineState& state, ShadingMode shading);

// The names the file format uses, shared with the command line.
const char* compareOpName(CompareOp op);
const char* cullModeName(CullMode mode);
const char* frontFaceName(FrontFace face);
const char* shadingModeName(ShadingMode mode);

}  // namespace rast
