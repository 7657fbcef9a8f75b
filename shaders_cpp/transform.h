// Vertex shaders for meshes.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "pipeline/shader.h"
#include "shaders_cpp/mesh_vertex.h"

namespace rast {

// Position only: model-view-projection, no varyings.
struct TransformVertexShader {
  using Vertex = MeshVertex;
  static constexpr int kVaryings = 0;
  glm::mat4 modelViewProjection{1.0f};

  ShadedVertex<0> operator()(const Vertex& v) const {
    return {modelViewProjection * glm::vec4(v.position, 1.0f), {}};
  }
};

// Passes on the world-space normal (varyings 0..2) and position (3..5), in that order, so a
// shader that needs only the normal reads (and pays for) three varyings.
struct WorldNormalVertexShader {
  using Vertex = MeshVertex;
  static constexpr int kVaryings = 6;
  glm::mat4 model{1.0f};
  glm::mat4 viewProjection{1.0f};

  ShadedVertex<6> operator()(const Vertex& v) const {
    const glm::vec4 world = model * glm::vec4(v.position, 1.0f);
    // Normals transform with the inverse transpose; for the rigid and uniformly scaled models
    // used here the model matrix itself gives the same direction.
    const glm::vec3 n = glm::mat3(model) * v.normal;
    return {viewProjection * world, {n.x, n.y, n.z, world.x, world.y, world.z}};
  }
};

}  // namespace rast
