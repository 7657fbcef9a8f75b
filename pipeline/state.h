// Pipeline state: everything a draw needs besides its vertices and shaders. Read once per draw;
// the back end is specialised on it (see draw.h), so nothing here is tested per pixel.
#pragma once

#include <optional>

#include <glm/vec4.hpp>

#include "pipeline/blend.h"
#include "rasterizer/edge_function.h"
#include "pipeline/depth_format.h"
#include "rasterizer/fixed_point.h"
#include "rasterizer/pixel_rect.h"

namespace rast {

enum class CullMode { None, Back, Front };

// Winding as seen on the displayed image (row 0 at the top), the same picture OpenGL shows, so
// CounterClockwise here is OpenGL's default front face.
enum class FrontFace { CounterClockwise, Clockwise };

enum class CompareOp { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };

// Where the vertex shader's positions live.
//   Clip:   homogeneous clip space, OpenGL conventions (-w <= x, y, z <= w), mapped through the
//           viewport with y flipped so window y points down, and depth = 0.5 * z/w + 0.5.
//   Window: already window coordinates (x, y in pixels, y down, z in [0, 1]) with w = 1; snapped
//           as given, for coverage comparisons with other rasterizers.
enum class PositionSpace { Clip, Window };

// How coverage is computed. FixedPoint: snapped vertices, exact integer edge functions and the
// top-left rule. Float: what a naive renderer does, float edge functions of the unsnapped
// vertices and no fill rule (rasterizer/float_coverage.h), for precision studies; the fixed-point
// format still bounds the guard band.
enum class RasterMode { FixedPoint, Float };

struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;  // pixels, top-left origin
};

struct DepthState {
  CompareOp compare = CompareOp::Less;
  bool write = true;
  // Test before the pixel shader (skipping shading of hidden fragments). Off moves the test
  // after shading, to measure what early depth saves; results are identical either way.
  bool early = true;
  // What the depth buffer stores (depth_format.h): fragments are quantised to it before the
  // compare and the write (the pixel shader's Fragment::depth is the interpolated value, as
  // shaders on hardware see it). Clear values should be
  // representable in it (0 and 1 are in every format).
  DepthFormat format = DepthFormat::Float32;
};
// With compare Always no test runs: merge.depth_passed and merge.depth_failed count nothing (with
// Never every covered sample fails). Always with writes off costs no depth access at all.

// What a draw clears the framebuffer to before it draws: a render pass's load op "clear", as a
// GPU's fast clear. Every colour and depth sample of the whole framebuffer (not only the viewport
// or scissor) gets the bits Framebuffer::clear(color, depth) would give it, but tile by tile in
// the back end: a touched tile starts from the values instead of being read back, an untouched
// one is written with them, and no separate pass writes the framebuffer first. Counts are not
// cleared (Framebuffer::clearCounts). A draw that fails validation clears nothing.
struct ClearValues {
  glm::vec4 color{0.0f};
  float depth = 1.0f;
};

struct PipelineState {
  Viewport viewport;
  std::optional<PixelRect> scissor;
  PositionSpace positionSpace = PositionSpace::Clip;
  FixedPointFormat format = FixedPointFormat::d24_4();
  RasterMode rasterMode = RasterMode::FixedPoint;
  CullMode cullMode = CullMode::None;
  FrontFace frontFace = FrontFace::CounterClockwise;
  FillRule fillRule = FillRule::TopLeft;  // BottomLeft: llvmpipe's, as its image is shown
  DepthState depth;
  bool colorWrite = true;               // false: no colour access at all (a depth-only pass)
  uint8_t colorWriteMask = kWriteAll;   // channels written when colorWrite is on
  BlendState blend;
  std::optional<ClearValues> clear;  // none: the draw starts from the framebuffer's contents
};

}  // namespace rast
