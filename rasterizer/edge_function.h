// Exact integer edge functions and the top-left fill rule.
//
// Window coordinates have y pointing down. For an edge from `from` to `to`,
//   E(p) = (to.x - from.x) * (p.y - from.y) - (to.y - from.y) * (p.x - from.x) = a*p.x + b*p.y + c
// is positive on the interior side of every edge of a triangle whose vertices run clockwise on the
// screen (TriangleSetup orders them so). All values are exact in int64_t (see fixed_point.h).
#pragma once

#include <cstdint>

namespace rast {

struct SnappedPoint {
  int32_t x = 0;  // subpixels
  int32_t y = 0;
  friend constexpr bool operator==(SnappedPoint, SnappedPoint) = default;
};

// Which edges own the samples exactly on them. TopLeft is Direct3D's rule in our window
// coordinates (y down). BottomLeft is the same rule mirrored vertically: what Mesa llvmpipe does
// when its bottom-up GL framebuffer is shown with row 0 at the top (README, "Conformance with
// llvmpipe"): left edges and the horizontal edges with the interior above them.
enum class FillRule { TopLeft, BottomLeft };

struct EdgeFunction {
  // |a|, |b| <= 2^27 (vertex differences, fixed_point.h), so they are stored in 32 bits (a set-up
  // triangle is 24 bytes smaller); every product with them is taken in int64.
  int32_t a = 0;  // dE/dx per subpixel
  int32_t b = 0;  // dE/dy per subpixel
  int64_t c = 0;  // includes the fill-rule bias: a sample is covered when E >= 0

  int64_t at(int64_t x, int64_t y) const { return int64_t{a} * x + int64_t{b} * y + c; }

  // Top-left rule, for a clockwise (on screen, y down) triangle: a sample exactly on an edge is
  // covered only if the edge is a left edge (interior to its right, E grows with x: a > 0) or a
  // top edge (horizontal, interior below, E grows with y: a == 0 && b > 0). Of two triangles
  // sharing an edge, exactly one sees it as top-left (a and b flip sign with the direction), so a
  // sample on the shared edge is covered once. Non-top-left edges are biased by -1, turning the
  // strict test E > 0 into E >= 0 on integers.
  static bool isTopLeft(int64_t a, int64_t b) { return a > 0 || (a == 0 && b > 0); }
  // BottomLeft: left edges, and horizontal edges with the interior above (E falls with y: b < 0).
  static bool ownsTies(int64_t a, int64_t b, FillRule rule) {
    return rule == FillRule::TopLeft ? isTopLeft(a, b) : a > 0 || (a == 0 && b < 0);
  }

  static EdgeFunction through(SnappedPoint from, SnappedPoint to,
                              FillRule rule = FillRule::TopLeft) {
    const int64_t a = int64_t(from.y) - to.y, b = int64_t(to.x) - from.x;
    EdgeFunction e;
    e.a = int32_t(a);
    e.b = int32_t(b);
    e.c = -(a * from.x + b * from.y) - (ownsTies(a, b, rule) ? 0 : 1);
    return e;
  }
};

}  // namespace rast
