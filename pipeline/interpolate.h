// Interpolation at a pixel centre: depth linearly in screen space, varyings perspective-correct
// (v/w and 1/w are linear in screen space; one division per pixel recovers v).
#pragma once

#include "pipeline/setup.h"

namespace rast {

// (dx, dy): the pixel's offset from the triangle's anchor pixel (bounds.x0, bounds.y0).
template <int N>
float interpolateDepth(const SetupTriangle<N>& t, float dx, float dy) {
  const float z = t.depth.at(dx, dy);
  // Extrapolating the plane to a pixel centre a rounding step outside the vertices' depth range
  // must not leave [0, 1], the range of every depth format.
  return z < 0.0f ? 0.0f : (z > 1.0f ? 1.0f : z);
}

template <int N>
void interpolateVaryings(const SetupTriangle<N>& t, float dx, float dy, Varyings<N>& out) {
  if constexpr (N > 0) {
    const float w = 1.0f / t.invW.at(dx, dy);
    for (int k = 0; k < N; ++k) out[k] = t.varyingsOverW[k].at(dx, dy) * w;
  }
}

}  // namespace rast
