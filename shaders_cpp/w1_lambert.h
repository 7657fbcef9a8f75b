#pragma once

#include <algorithm>
#include <glm/geometric.hpp>

#include "pipeline/shader.h"

namespace rast {

// The W1 benchmark's pixel shader (bench/workloads.h; the peer's GLSL does the same): directional
// Lambert from the interpolated normal, varyings 0..2 of WorldNormalVertexShader. It reads only
// those three, so the world position the vertex shader also writes is never interpolated.
struct W1LambertShader {
  static constexpr int kVaryings = 3;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kWholeRows = true;  // any input is safe (shader.h)
  glm::vec3 lightDirection = glm::normalize(glm::vec3(0.35f, 0.55f, 0.76f));  // towards the light

  PixelResult operator()(const Fragment<3>& f) const {
    const glm::vec3 n = glm::normalize(glm::vec3(f.varyings[0], f.varyings[1], f.varyings[2]));
    const float diffuse = std::max(glm::dot(n, lightDirection), 0.0f);
    return {glm::vec4(0.08f + diffuse * glm::vec3(0.85f, 0.80f, 0.70f), 1.0f)};
  }
};

}  // namespace rast
