#pragma once

#include <glm/geometric.hpp>

#include "pipeline/shader.h"

namespace rast {

// The interpolated normal (varyings 0..2) as a colour, n * 0.5 + 0.5.
struct NormalVisualizerShader {
  static constexpr int kVaryings = 3;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kWholeRows = true;  // any input is safe (shader.h)

  PixelResult operator()(const Fragment<3>& f) const {
    const glm::vec3 n = glm::normalize(glm::vec3(f.varyings[0], f.varyings[1], f.varyings[2]));
    return {glm::vec4(n * 0.5f + 0.5f, 1.0f)};
  }
};

}  // namespace rast
