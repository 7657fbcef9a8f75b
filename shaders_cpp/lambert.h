#pragma once

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/shader.h"

namespace rast {

// Diffuse (Lambert) shading with a point light, from the interpolated world normal (varyings
// 0..2) and world position (3..5) of WorldNormalVertexShader. Back faces are lit from their own
// side, so open meshes look right from inside too.
struct LambertShader {
  static constexpr int kVaryings = 6;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kWholeRows = true;  // any input is safe (shader.h)
  glm::vec3 albedo{0.8f};
  glm::vec3 ambient{0.08f};
  glm::vec3 lightPosition{0.0f, 10.0f, 10.0f};
  glm::vec3 lightColor{1.0f};

  PixelResult operator()(const Fragment<6>& f) const {
    glm::vec3 n = glm::normalize(glm::vec3(f.varyings[0], f.varyings[1], f.varyings[2]));
    if (!f.frontFacing) n = -n;
    const glm::vec3 p(f.varyings[3], f.varyings[4], f.varyings[5]);
    const glm::vec3 l = glm::normalize(lightPosition - p);
    const float diffuse = std::max(glm::dot(n, l), 0.0f);
    return {glm::vec4(ambient + albedo * lightColor * diffuse, 1.0f)};
  }
};

}  // namespace rast
