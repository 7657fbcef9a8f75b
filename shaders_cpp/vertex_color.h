#pragma once

#include <glm/mat4x4.hpp>

#include "pipeline/shader.h"

namespace rast {

struct ColoredVertex {
  glm::vec3 position{0.0f};
  glm::vec4 color{1.0f};
};

// Passes the vertex colour on as varyings 0..3.
struct VertexColorVertexShader {
  using Vertex = ColoredVertex;
  static constexpr int kVaryings = 4;
  glm::mat4 modelViewProjection{1.0f};

  ShadedVertex<4> operator()(const Vertex& v) const {
    return {modelViewProjection * glm::vec4(v.position, 1.0f),
            {v.color.r, v.color.g, v.color.b, v.color.a}};
  }
};

// The interpolated vertex colour.
struct VertexColorShader {
  static constexpr int kVaryings = 4;
  static constexpr bool kMayDiscard = false;

  PixelResult operator()(const Fragment<4>& f) const {
    return {glm::vec4(f.varyings[0], f.varyings[1], f.varyings[2], f.varyings[3])};
  }
};

}  // namespace rast
