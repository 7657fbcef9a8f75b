#pragma once

#include "pipeline/shader.h"

namespace rast {

// One colour for every fragment.
struct ConstantColorShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kPerTriangle = true;  // shaded once per triangle and tile
  glm::vec4 color{1.0f};

  PixelResult operator()(const Fragment<0>&) const { return {color}; }
};

}  // namespace rast
