// Viewport transform and the planes that bound what reaches fixed point.
//
// window = (position.xyz / position.w) * scale + offset, computed in double. Every test below is a
// half-space dot(plane, position) >= 0 in the vertex shader's output space, equivalent to a bound
// on the window coordinate when w > 0:
//   window.x >= L  <=>  scale.x * x + (offset.x - L) * w >= 0
//   window.x <= U  <=>  -scale.x * x + (U - offset.x) * w >= 0
// so clip space and window space (scale 1, offset 0, w = 1) share one clipper.
#pragma once

#include <array>
#include <cmath>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "pipeline/state.h"
#include "rasterizer/double_double.h"

namespace rast {

using ClipPlane = glm::dvec4;

struct WindowPosition {
  double x, y, z;  // pixels (y down) and depth in [0, 1]
  double invW;
};

struct ScreenMapping {
  glm::dvec3 scale{1.0};
  glm::dvec3 offset{0.0};

  static ScreenMapping forState(const PipelineState& state);

  WindowPosition toWindow(const glm::dvec4& p) const {
    const double invW = 1.0 / p.w;
    return {double(p.x) * invW * scale.x + offset.x, double(p.y) * invW * scale.y + offset.y,
            double(p.z) * invW * scale.z + offset.z, invW};
  }

  ClipPlane windowAtLeast(int axis, double bound) const;  // window[axis] >= bound
  ClipPlane windowAtMost(int axis, double bound) const;   // window[axis] <= bound
};

// Planes a triangle is tested against, in the order they are applied.
struct ClipPlanes {
  // Trivial rejection: all three vertices outside one of these means nothing is drawn. The
  // viewport's four sides (a triangle beyond them covers no pixel centre of the viewport) and
  // depth 0 and 1.
  std::array<ClipPlane, 6> reject;
  // Clipping: w >= 0, depth 0 (the near plane), depth 1 (the far plane), and the four sides of
  // the guard band, beyond which fixed point would overflow (fixed_point.h). Triangles are cut
  // here, so every vertex that reaches snapping lies in the guard band. Each plane bounds one
  // window axis (or w), which the clipper relies on to place new vertices exactly on it.
  static constexpr int kClipPlaneCount = 7;
  std::array<ClipPlane, kClipPlaneCount> clip;

  static ClipPlanes forState(const PipelineState& state, const ScreenMapping& mapping);
};

// dot(plane, p) in double-double (about 106 bits): a vertex far outside a plane has terms that
// nearly cancel, and the clipper needs the small remainder to place its new vertex.
inline DoubleDouble signedDistanceExact(const ClipPlane& plane, const glm::dvec4& p) {
  DoubleDouble sum = DoubleDouble::product(plane[0], p[0]);
  for (int i = 1; i < 4; ++i) sum = sum + DoubleDouble::product(plane[i], p[i]);
  return sum;
}

inline double signedDistance(const ClipPlane& plane, const glm::dvec4& p) {
  return signedDistanceExact(plane, p).hi;
}

}  // namespace rast
