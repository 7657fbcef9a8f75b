#pragma once

#include <glm/vec3.hpp>

#include "pipeline/shader.h"

namespace rast {

// A vertex already in window coordinates: x, y in pixels (y down), z in [0, 1].
struct WindowVertex {
  glm::vec3 position{0.0f};
};

// Hands window positions through unchanged (w = 1); draw with PositionSpace::Window.
struct WindowSpaceVertexShader {
  using Vertex = WindowVertex;
  static constexpr int kVaryings = 0;

  ShadedVertex<0> operator()(const Vertex& v) const { return {glm::vec4(v.position, 1.0f), {}}; }
};

}  // namespace rast
