// Shadow-map lookups: a read-only view of a light pass's depth plane (a draw from the light with
// colour writes off into its own Framebuffer) and the depth comparison a pixel shader makes.
//
// The camera pass's vertex shader outputs each vertex's light-space clip position as varyings;
// they are interpolated perspective-correctly (clip coordinates are linear in world space) and
// divided per pixel here, then mapped like the light pass's viewport (0, 0, width, height): x to
// the right, y down, depth 0.5 * z/w + 0.5. The light pass stored, per texel, the depth at the
// texel's centre, so the texel a point falls in is the nearest sample.
//
// Depth bias: the point is lit by a texel when  depth - bias <= stored  (the light pass used
// CompareOp::Less). The bias is in window-depth units; it absorbs the difference between the
// receiver's depth at the point and at the texel centre (up to half a texel times the depth
// slope), which otherwise shadows a lit surface by itself (acne).
//
// Percentage-closer filtering: the fraction of the k x k texels around that texel (k = 1, 3, 5)
// that light the point. A point outside the map, behind the light (w <= 0) or beyond its far
// plane is lit: what the light pass did not see cannot cast a shadow.
#pragma once

#include <cmath>

#include <glm/vec4.hpp>

#include "pipeline/framebuffer.h"

namespace rast {

struct ShadowMap {
  const float* depth = nullptr;  // row-major, row 0 at the top
  int width = 0, height = 0;

  static ShadowMap of(const Framebuffer& lightPass) {
    return {lightPass.depthPlane().data(), lightPass.width(), lightPass.height()};
  }

  // Visibility in [0, 1] of the point at light-space clip position `clip`; pcf is 1, 3 or 5.
  float visibility(glm::vec4 clip, float bias, int pcf = 1) const {
    if (!(clip.w > 0.0f)) return 1.0f;
    const float invW = 1.0f / clip.w;
    const float x = (clip.x * invW * 0.5f + 0.5f) * float(width);
    const float y = (clip.y * invW * -0.5f + 0.5f) * float(height);
    const float z = clip.z * invW * 0.5f + 0.5f;
    // Beyond the map (NaN included): lit. The bounds keep the integer conversion in range.
    if (!(x >= -8.0f && x < float(width) + 8.0f && y >= -8.0f && y < float(height) + 8.0f &&
          z <= 1.0f))
      return 1.0f;
    const int tx = int(std::floor(x)), ty = int(std::floor(y));
    const int r = pcf / 2;
    int lit = 0;
    for (int j = ty - r; j <= ty + r; ++j)
      for (int i = tx - r; i <= tx + r; ++i)
        lit += i < 0 || j < 0 || i >= width || j >= height ||
               z - bias <= depth[size_t(j) * size_t(width) + size_t(i)];
    return float(lit) / float((2 * r + 1) * (2 * r + 1));
  }
};

}  // namespace rast
