// Triangle setup for coverage: orientation, zero-area rejection, edge functions with the fill rule,
// and the bounding box of the pixel centres the triangle can cover.
#pragma once

#include <array>
#include <cstdint>

#include "rasterizer/edge_function.h"
#include "rasterizer/fixed_point.h"
#include "rasterizer/pixel_rect.h"

namespace rast {

enum class SetupOutcome {
  Accepted,
  ZeroArea,   // the snapped vertices are collinear
  NoSamples,  // the bounding box, clipped to `clip`, holds no pixel centre; or, for a triangle
              // narrower and shorter than two pixels without MSAA, none of those it holds is
              // covered
};

struct CoverageSetup {
  std::array<EdgeFunction, 3> edges;  // positive inside; edge i runs from vertex i to i+1
  PixelRect bounds;                   // pixels whose centres may be covered, inside `clip`
  bool clockwiseOnScreen = false;     // winding of the input order, before reordering
  int64_t doubleArea = 0;             // twice the area in subpixels^2, > 0
};

// `v` are the snapped vertices in submission order. When they run counter-clockwise on screen, the
// edges are built for the order (v0, v2, v1) so that the interior is positive; `reordered` says so.
// `sampleReach`: how far (subpixels, per axis) a pixel's samples lie from its centre (MSAA), so
// the bounds take in every pixel with a sample inside the vertices' bounding box.
SetupOutcome setupCoverage(const std::array<SnappedPoint, 3>& v, const PixelRect& clip,
                           FixedPointFormat format, CoverageSetup& out,
                           FillRule rule = FillRule::TopLeft, int32_t sampleReach = 0);

}  // namespace rast
