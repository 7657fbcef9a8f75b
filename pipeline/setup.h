// Triangle setup in the pipeline: viewport transform and snapping, coverage setup (edge
// functions, fill rule, bounds), culling, and the plane equations the back end interpolates.
#pragma once

#include <array>
#include <type_traits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "pipeline/shader.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "pipeline/viewport.h"
#include "rasterizer/float_coverage.h"
#include "rasterizer/plane_equation.h"
#include "rasterizer/triangle_setup.h"

namespace rast {

// Stand-ins for members a triangle does not have (no varyings, no padding): distinct empty
// types, so that [[no_unique_address]] lets them all take no room (std::array<T, 0> takes a byte).
struct NoPlane {};
struct NoVaryingPlanes {};
struct NoPadding {};

// The largest framebuffer side a draw accepts (validateDraw), so that a set-up triangle's bounds,
// which lie within the framebuffer, fit 16 bits a coordinate. Direct3D's limit is half of it.
inline constexpr int kMaxFramebufferSide = 32768;

// A set-up triangle's bounds, PixelRect's values in 16 bits each (all lie in [0,
// kMaxFramebufferSide]): eight bytes fewer than PixelRect's, which took the triangle with three
// varyings from 136 bytes to 128, two cache lines instead of three for every read of it in the
// back end and every write of it in setup (lines which on this machine often cross from one core
// complex to the other).
struct TriangleBounds {
  uint16_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  TriangleBounds() = default;
  TriangleBounds(int left, int top, int right, int bottom)
      : x0(uint16_t(left)), y0(uint16_t(top)), x1(uint16_t(right)), y1(uint16_t(bottom)) {}
  explicit TriangleBounds(const PixelRect& r) : TriangleBounds(r.x0, r.y0, r.x1, r.y1) {}
  // Forced inline: the tile loop converts per entry, and GCC left it a call there.
  [[gnu::always_inline]] operator PixelRect() const { return {x0, y0, x1, y1}; }
  friend bool operator==(const TriangleBounds&, const TriangleBounds&) = default;
};
static_assert(kMaxFramebufferSide <= std::numeric_limits<uint16_t>::max());

// A set-up triangle with N varyings takes 72 bytes, 12 more for 1/w when N > 0, and 12 per
// varying. Where that falls 8 bytes or less short of whole cache lines (three varyings: 120), it
// is padded to them (128), so that the back end's fetch of a triangle from a 64-byte-aligned
// chunk takes whole lines: at 120 bytes six triangles in eight straddle three lines.
constexpr size_t setupTrianglePadding(int n) {
  const size_t bytes = 72 + (n > 0 ? 12 : 0) + 12 * size_t(n);
  return bytes % 64 >= 56 ? 64 - bytes % 64 : 0;
}

// What coverage and the depth test read of a set-up triangle, the same for every number of
// varyings: the part the back end's kernels take (rect_early_depth.h) whatever the shader.
struct RasterTriangle {
  std::array<EdgeFunction, 3> edges;
  TriangleBounds bounds;  // planes are anchored at the centre of pixel (bounds.x0, bounds.y0)
  PlaneEquation depth;
  // The primitive id in bits 0 to 30 (a draw holds at most 2^28 triangles, validateDraw, and a
  // clipped triangle's pieces keep its id) and whether it faces the viewer in bit 31: four bytes
  // where a separate flag took eight with its padding.
  uint32_t primitiveAndFacing = 0;

  static constexpr uint32_t kFrontFacingBit = uint32_t{1} << 31;
  uint32_t primitiveId() const { return primitiveAndFacing & ~kFrontFacingBit; }
  bool frontFacing() const { return (primitiveAndFacing & kFrontFacingBit) != 0; }
  void setPrimitive(uint32_t id, bool front) {
    primitiveAndFacing = id | (front ? kFrontFacingBit : 0);
  }
};

// Everything the back end needs of one triangle. N: varyings the pixel shader reads.
// Kept small, since a draw writes one per triangle and the back end reads it once per tile it
// touches (W2 tiny-1: two million a frame): with no varyings it is 72 bytes, with three 128. 1/w
// is stored only when there are varyings to correct, and float mode's edges live beside the
// triangles (SetupTriangles::floatChunks).
template <int N>
struct SetupTriangle : RasterTriangle {
  [[no_unique_address]] std::conditional_t<(N > 0), PlaneEquation, NoPlane> invW;
  [[no_unique_address]] std::conditional_t<(N > 0), std::array<PlaneEquation, N>, NoVaryingPlanes>
      varyingsOverW;
  [[no_unique_address]] std::conditional_t<(setupTrianglePadding(N) > 0),
                                           std::array<std::byte, setupTrianglePadding(N)>, NoPadding>
      padding;
};
static_assert(sizeof(SetupTriangle<0>) == 72 && sizeof(SetupTriangle<3>) == 128);

// Draw-time constants of setup.
struct SetupContext {
  ScreenMapping mapping;
  FixedPointFormat format;
  PixelRect clipRect;  // viewport, scissor and framebuffer, intersected
  CullMode cullMode;
  FrontFace frontFace;
  FillRule fillRule = FillRule::TopLeft;
  int32_t sampleReach = 0;  // subpixels from a pixel centre to its farthest MSAA sample
  RasterMode rasterMode = RasterMode::FixedPoint;
};

// Whether a triangle faces the viewer.
inline bool facesFront(bool clockwiseOnScreen, const SetupContext& ctx) {
  return clockwiseOnScreen == (ctx.frontFace == FrontFace::Clockwise);
}

// What becomes of a triangle after coverage setup: drawn, or dropped and why.
enum class SetupVerdict : int32_t { Drawn, ZeroArea, CulledBack, CulledFront, NoSamples };
inline constexpr int kSetupVerdicts = 5;

// Without branches, so that SetupBatch's loop over its lanes vectorises: which small triangles
// cover no sample is as good as random (W2 tiny-1: a sixth of them), and a mispredicted branch
// per triangle costs more than these tests. Shared with SetupBatch (setup_batch.h), so that both
// decide and count the same way.
inline SetupVerdict judgeCoverage(SetupOutcome outcome, bool clockwiseOnScreen,
                                  const SetupContext& ctx) {
  const bool front = facesFront(clockwiseOnScreen, ctx);
  const bool culled = (ctx.cullMode == CullMode::Back && !front) ||
                      (ctx.cullMode == CullMode::Front && front);
  return outcome == SetupOutcome::ZeroArea  ? SetupVerdict::ZeroArea
         : culled                           ? (front ? SetupVerdict::CulledFront
                                                     : SetupVerdict::CulledBack)
         : outcome == SetupOutcome::NoSamples ? SetupVerdict::NoSamples
                                              : SetupVerdict::Drawn;
}

// Counts `count` triangles dropped for `verdict` (nothing for Drawn).
inline void countDropped(SetupVerdict verdict, uint64_t count, PipelineStatistics& stats) {
  switch (verdict) {
    case SetupVerdict::Drawn: break;
    case SetupVerdict::ZeroArea: stats.setupZeroArea += count; break;
    case SetupVerdict::CulledBack: stats.setupCulledBack += count; break;
    case SetupVerdict::CulledFront: stats.setupCulledFront += count; break;
    case SetupVerdict::NoSamples: stats.setupNoSamples += count; break;
  }
}

// Sets up one triangle whose vertices lie inside the guard band (the clipper made sure). Returns
// false, having counted why, when it draws nothing. In float mode the float edges go to
// `floatEdges`.
// V: ShadedVertex<N> (unclipped) or ClippedVertex<N>, with `position` and `varyings`.
template <int N, class V>
bool setupTriangle(const std::array<const V*, 3>& v, const SetupContext& ctx,
                   uint32_t primitiveId, SetupTriangle<N>& out, FloatEdges& floatEdges,
                   PipelineStatistics& stats) {
  std::array<WindowPosition, 3> w;
  for (int i = 0; i < 3; ++i) {
    w[i] = ctx.mapping.toWindow(glm::dvec4(v[i]->position));
    if (!std::isfinite(w[i].x) || !std::isfinite(w[i].y) || !std::isfinite(w[i].z) ||
        !std::isfinite(w[i].invW)) {
      ++stats.clipDegenerate;
      return false;
    }
  }
  std::array<SnappedPoint, 3> snapped;
  for (int i = 0; i < 3; ++i)
    snapped[i] = {snapToSubpixels(w[i].x, ctx.format), snapToSubpixels(w[i].y, ctx.format)};

  CoverageSetup coverage;
  const bool floatMode = ctx.rasterMode == RasterMode::Float;
  const SetupOutcome outcome =
      floatMode ? setupFloatCoverage({w[0].x, w[1].x, w[2].x}, {w[0].y, w[1].y, w[2].y},
                                     ctx.clipRect, coverage, floatEdges)
                : setupCoverage(snapped, ctx.clipRect, ctx.format, coverage, ctx.fillRule,
                                ctx.sampleReach);
  const SetupVerdict verdict = judgeCoverage(outcome, coverage.clockwiseOnScreen, ctx);
  countDropped(verdict, 1, stats);
  if (verdict != SetupVerdict::Drawn) return false;

  out.edges = coverage.edges;
  out.bounds = TriangleBounds(coverage.bounds);
  out.setPrimitive(primitiveId, facesFront(coverage.clockwiseOnScreen, ctx));

  // Planes through the snapped positions (float mode: the float ones), so interpolation agrees
  // with the coverage it serves.
  std::array<double, 3> x, y, depth, invW;
  for (int i = 0; i < 3; ++i) {
    // (Float mode widens the floats setupFloatCoverage stored, not double(float(w[i].x)) here:
    // GCC 12 at -O2 and above drops that rounding in one lane of the vectorized loop.)
    x[i] = floatMode ? floatEdges.x[i] : subpixelsToPixels(snapped[i].x, ctx.format);
    y[i] = floatMode ? floatEdges.y[i] : subpixelsToPixels(snapped[i].y, ctx.format);
    depth[i] = w[i].z;
    invW[i] = w[i].invW;
  }
  const double signedArea = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const double inv = 1.0 / signedArea;
  const int ax = out.bounds.x0, ay = out.bounds.y0;
  out.depth = PlaneEquation::through(x, y, depth, inv, ax, ay);
  if constexpr (N > 0) {
    out.invW = PlaneEquation::through(x, y, invW, inv, ax, ay);
    for (int k = 0; k < N; ++k) {
      std::array<double, 3> overW;
      for (int i = 0; i < 3; ++i) overW[i] = double(v[i]->varyings[k]) * w[i].invW;
      out.varyingsOverW[k] = PlaneEquation::through(x, y, overW, inv, ax, ay);
    }
  }
  ++stats.setupTriangles;
  return true;
}

}  // namespace rast
