// Plane equations for attributes that are linear in screen space (depth z/w, 1/w, varying/w).
//
// Coefficients are computed in double from the snapped vertex positions and stored in float,
// relative to the centre of an anchor pixel (the triangle's bounds origin), so the per-pixel
// offsets dx, dy are small integers and exact in float. Evaluation is (at0 + ddx*dx) + ddy*dy in
// float, in that order, with no fused multiply-add (the build sets -ffp-contract=off): every
// kernel, scalar or SIMD, that evaluates a plane this way gets the same bits.
#pragma once

#include <array>

namespace rast {

struct PlaneEquation {
  float at0 = 0;  // value at the centre of the anchor pixel
  float ddx = 0;  // per pixel to the right
  float ddy = 0;  // per pixel down

  float at(float dx, float dy) const { return (at0 + ddx * dx) + ddy * dy; }

  // The plane through (x[i], y[i], value[i]), positions in pixels, anchored at pixel centre
  // (anchorX + 0.5, anchorY + 0.5). `inverseDoubleArea` is 1 / ((x1-x0)(y2-y0) - (x2-x0)(y1-y0)).
  static PlaneEquation through(const std::array<double, 3>& x, const std::array<double, 3>& y,
                               const std::array<double, 3>& value, double inverseDoubleArea,
                               int anchorX, int anchorY) {
    const double d1 = value[1] - value[0], d2 = value[2] - value[0];
    const double ddx = (d1 * (y[2] - y[0]) - d2 * (y[1] - y[0])) * inverseDoubleArea;
    const double ddy = (d2 * (x[1] - x[0]) - d1 * (x[2] - x[0])) * inverseDoubleArea;
    const double at0 = value[0] + ddx * (anchorX + 0.5 - x[0]) + ddy * (anchorY + 0.5 - y[0]);
    return {float(at0), float(ddx), float(ddy)};
  }
};

}  // namespace rast
