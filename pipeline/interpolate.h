// Interpolation at a pixel centre: depth linearly in screen space, varyings perspective-correct
// (v/w and 1/w are linear in screen space; one division per pixel recovers v).
#pragma once

#include <xmmintrin.h>

#include "pipeline/setup.h"

namespace rast {

// (dx, dy): the pixel's offset from the triangle's anchor pixel (bounds.x0, bounds.y0).
// Forced inline: the back end's few-pixel depth test calls it per pixel, and in the depth-only
// tile loop (W4's) GCC left it a call, 9 % of the frame.
template <int N>
[[gnu::always_inline]] inline float interpolateDepth(const SetupTriangle<N>& t, float dx, float dy) {
  const float z = t.depth.at(dx, dy);
  // Extrapolating the plane to a pixel centre a rounding step outside the vertices' depth range
  // must not leave [0, 1], the range of every depth format.
  // z < 0 ? 0 : (z > 1 ? 1 : z) as minss(1, z) = (1 < z ? 1 : z), then maxss(0, that) (its sign
  // is z's wherever it matters): the same bits, NaN and -0 included, in two instructions whatever
  // the compiler's float options (under -fno-trapping-math GCC made the ternaries conditional
  // moves through integer registers).
  return _mm_cvtss_f32(_mm_max_ss(_mm_setzero_ps(), _mm_min_ss(_mm_set_ss(1.0f), _mm_set_ss(z))));
}

template <int N>
void interpolateVaryings(const SetupTriangle<N>& t, float dx, float dy, Varyings<N>& out) {
  if constexpr (N > 0) {
    const float w = 1.0f / t.invW.at(dx, dy);
    for (int k = 0; k < N; ++k) out[k] = t.varyingsOverW[k].at(dx, dy) * w;
  }
}

}  // namespace rast
