// An exact reference rasterizer: slow, per sample, and obviously correct. Coverage of window-space
// triangles decided by exact integer predicates (__int128, no overflow possible), and a double
// precision oracle for depth and perspective-correct varyings.
//
// Input is window positions (x, y in pixels, y down, as PositionSpace::Window takes them, or the
// double values ScreenMapping::toWindow gives the pipeline for clip-space vertices): clipping is
// not modelled, so clip-space triangles must lie in front of the eye, in the depth range and
// inside the guard band, where the pipeline does not clip them either.
//
// Two geometries:
//   * Snapped to a FixedPointFormat: each coordinate rounded to the nearest 1/2^F pixel, ties to
//     even (decided here from the exact fractional part, not by std::nearbyint), then clamped to
//     the guard band, the same snapping the pipeline documents (fixed_point.h).
//   * Exact: the given coordinates themselves. Every double is a dyadic rational, so the triangle
//     and the samples are put on a common grid of 1/2^G pixel with G as small as the inputs
//     allow; when that grid needs integers beyond 2^61 (a coordinate with too many fraction bits
//     for its magnitude; never for float-valued window coordinates below 2^20 with no nonzero
//     |value| under 2^-30) the triangle is reported as undecidable instead of guessed.
// Samples are pixel centres (x + 1/2, y + 1/2), so they lie on every grid with G >= 1.
//
// Fill rule: a sample strictly inside is covered; a sample exactly on an edge is covered when that
// edge is a top edge (horizontal, the triangle below it on screen) or a left edge (not
// horizontal, the triangle to its right), decided from the third vertex, not from the edge
// function's coefficients. Zero-area (collinear) triangles cover nothing. No culling.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "rasterizer/fixed_point.h"
#include "rasterizer/pixel_rect.h"

namespace rast::reference {

struct WindowPoint {
  double x = 0, y = 0;  // pixels, y down
};
using WindowTriangle = std::array<WindowPoint, 3>;

enum class SampleRule {
  TopLeft,         // the pipeline's rule: shared edges covered exactly once
  ClosedTriangle,  // every sample on an edge covered (what "E >= 0" does in a naive renderer)
};

// Which geometry is rasterized: snapped to `format`, or exact (no snapping) when `snap` is false.
struct ExactGeometry {
  bool snap = true;
  FixedPointFormat format = FixedPointFormat::d24_4();
  SampleRule rule = SampleRule::TopLeft;
};

// A triangle on an integer grid of 1/2^fractionBits pixel.
struct GridTriangle {
  std::array<__int128, 3> x{}, y{};
  int fractionBits = 1;
};

// The triangle with each coordinate rounded to float (what float mode and PositionSpace::Window
// see). Through volatile storage: GCC 12 at -O2 and above drops the float rounding of the last
// lane of a vectorized loop of `double(float(v))`.
WindowTriangle roundedToFloat(const WindowTriangle& t);

// Round to nearest, ties to even, of v * 2^F, clamped to the format's guard band.
int64_t snapExactly(double v, FixedPointFormat format);

// The triangle on its grid; false when the exact geometry is undecidable (see above) or a
// coordinate is not finite.
bool toGrid(const WindowTriangle& t, const ExactGeometry& geometry, GridTriangle& out);

// Whether the centre of pixel (px, py) is covered.
bool coversPixelCentre(const GridTriangle& t, int px, int py, SampleRule rule);

// Calls visit(x, y) for each covered pixel centre inside `clip`, in row-major order.
void forEachCoveredPixel(const GridTriangle& t, const PixelRect& clip, SampleRule rule,
                         const std::function<void(int, int)>& visit);

struct CoverageCounts {
  int width = 0, height = 0;
  std::vector<uint32_t> counts;  // row-major, row 0 at the top: covering triangles per pixel
  uint64_t undecidable = 0;      // triangles toGrid refused (exact geometry only)
};

// Per pixel of a width x height image, how many of the triangles cover its centre.
CoverageCounts rasterizeCounts(std::span<const WindowTriangle> triangles, int width, int height,
                               const ExactGeometry& geometry);

// ---- The interpolation oracle.
//
// Barycentric coordinates of a pixel centre in the grid triangle: each is a ratio of two exact
// integers (sub-triangle area over triangle area) rounded once to double, so they carry a
// relative error of at most 2^-53 however thin the triangle. The oracle interpolates over the
// snapped triangle because the pipeline does: its attribute planes pass through the snapped
// positions, so that interpolation agrees with the coverage it serves and two triangles sharing an
// edge agree along it. What snapping itself moves (at most half a subpixel times the gradient) is
// a property of the geometry, not of the arithmetic the oracle checks. Requires nonzero area and
// a pixel centre inside the triangle's bounding box (every covered one is).
std::array<double, 3> barycentricAtPixelCentre(const GridTriangle& t, int px, int py);

// Window depth z/w is affine in screen space.
double interpolateLinear(const std::array<double, 3>& l, const std::array<double, 3>& value);
// v/w and 1/w are affine in screen space; v is their ratio.
double interpolatePerspective(const std::array<double, 3>& l, const std::array<double, 3>& invW,
                              const std::array<double, 3>& value);

}  // namespace rast::reference
