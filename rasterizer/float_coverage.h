// Float mode (RasterMode::Float): coverage as a naive renderer computes it, for comparison with
// the fixed-point pipeline. Window coordinates are rounded to float and not snapped; each edge is
// the fixed-point edge function's formula in float,
//   a = y_from - y_to, b = x_to - x_from, c = -(a * x_from + b * y_from)   (float, in that order)
//   E(p) = (a * p.x + b * p.y) + c                                         (float, no FMA)
// at pixel centres p in float, oriented so the interior is positive (the float area's sign), and
// a pixel centre is covered when it lies in the bounding box of the float vertices and E >= 0 on
// all three edges: no fill rule, so samples exactly on a shared edge are covered twice, and the
// rounding of c (which cancels against a*x + b*y) can leave a sample near a shared edge covered by
// both triangles or by neither. A triangle whose float area is zero covers nothing.
//
// Whole-tile tests are exact for this rule, as for the integer one: every operation of E is
// monotonic in p.x and in p.y (a float sum or product with a constant never reverses an order),
// so over a tile E takes its extremes at corner samples.
#pragma once

#include <array>

#include "rasterizer/coverage.h"
#include "rasterizer/coverage_kernels.h"
#include "rasterizer/pixel_rect.h"
#include "rasterizer/triangle_setup.h"

namespace rast {

struct FloatEdge {
  float a = 0, b = 0, c = 0;
  float at(float x, float y) const { return (a * x + b * y) + c; }
};

struct FloatEdges {
  std::array<FloatEdge, 3> edges;  // positive inside (for a counter-clockwise triangle, edge i
                                   // runs from vertex i to vertex i - 1)
  std::array<float, 3> x{}, y{};   // the vertices in float window coordinates (pixels), in the
                                   // order given
};

// Setup from window positions (pixels, y down): the float vertices, their edges, orientation and
// zero-area test on the float area, and the bounds of the pixel centres inside their bounding box
// (clipped to `clip`). Fills `out`'s bounds and winding like setupCoverage; its integer edges and
// area are left untouched. ZeroArea also when the area of the float vertices evaluated in double
// is zero, so that the attribute planes through them (setup.h) are defined.
SetupOutcome setupFloatCoverage(const std::array<double, 3>& windowX,
                                const std::array<double, 3>& windowY, const PixelRect& clip,
                                CoverageSetup& out, FloatEdges& edges);

// The coverage mask of one 8x8 tile, and whether its corners decided it (as coverTile).
TileCoverageResult coverTileFloat(const FloatEdges& edges, const PixelRect& bounds, int tileX,
                                  int tileY);
// The corner test alone (binning): Outside when some edge is negative at all four corners.
TileCoverage classifyTileFloat(const FloatEdges& edges, const PixelRect& bounds, int tileX,
                               int tileY);

}  // namespace rast
