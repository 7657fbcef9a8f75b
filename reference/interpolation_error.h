// Interpolation error of the pipeline against the exact reference's double-precision oracle
// (exact_rasterizer.h): one clip-space triangle with two varyings drawn through the real pipeline,
// every covered pixel's perspective-correct varyings and depth compared with the oracle over the
// same geometry (snapped in fixed-point mode, the float vertices in float mode).
//
// Two measures, in ULPs:
//   * value ULPs: |error| / ulp(exact value), the spacing of floats at the exact value. Not
//     bounded: a plane is evaluated as at0 + ddx dx + ddy dy from an anchor at the corner of the
//     triangle's bounding box, so where the terms are much larger than the value (depth near 0 on
//     a steep triangle, a varying crossing 0, a sliver whose bounding-box corner lies far from it
//     across a steep gradient) the error is many ULPs of the value.
//   * scale ULPs: |error| / (2^-24 S), with S the magnitude of the terms the float evaluation adds,
//     S = |at0| + |ddx dx| + |ddy dy| for depth, and for a varying u = q / r (q = u/w and r = 1/w
//     planes) S = (S_q + |u| S_r) / r + |u|. This is what float arithmetic can promise: a few.
#pragma once

#include <array>
#include <cstdint>

#include "pipeline/shader.h"
#include "pipeline/state.h"
#include "pipeline/status.h"

namespace rast::reference {

struct ErrorMaximum {
  double scaleUlps = 0, valueUlps = 0;
  uint64_t pixels = 0;
  void add(const ErrorMaximum& o);
};

struct InterpolationErrors {
  ErrorMaximum depth;
  std::array<ErrorMaximum, 2> varyings;
  // Screen-linear (affine) interpolation of varying 0 measured in the same scale ULPs: what a
  // renderer without perspective correction would score.
  double affineScaleUlps = 0;
  bool clipped = false;  // the pipeline clipped the triangle: nothing was measured
  void add(const InterpolationErrors& o);
};

// Draws `triangle` (clip space, two varyings) into a width x height viewport with `state`'s
// format and raster mode (its viewport and depth state are replaced) and measures every covered
// pixel. Triangles the clipper would cut are reported as `clipped`, not measured.
Status measureInterpolation(const std::array<ShadedVertex<2>, 3>& triangle, PipelineState state,
                            int width, int height, InterpolationErrors& out);

}  // namespace rast::reference
