// The vertex type of meshes (OBJ files, the built-in scene): position and normal.
#pragma once

#include <glm/vec3.hpp>

namespace rast {

struct MeshVertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
};

}  // namespace rast
