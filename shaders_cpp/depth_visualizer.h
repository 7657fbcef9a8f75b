#pragma once

#include "pipeline/shader.h"

namespace rast {

// Window depth as grey, stretched from [nearDepth, farDepth] to [1, 0] (near is bright), since
// perspective depth crowds most of a scene close to 1.
struct DepthVisualizerShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = false;
  float nearDepth = 0.0f;
  float farDepth = 1.0f;

  PixelResult operator()(const Fragment<0>& f) const {
    const float g = 1.0f - (f.depth - nearDepth) / (farDepth - nearDepth);
    return {glm::vec4(g, g, g, 1.0f)};
  }
};

}  // namespace rast
