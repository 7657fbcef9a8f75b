#pragma once

#include <algorithm>

namespace rast {

// A half-open rectangle of pixels [x0, x1) x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x0 >= x1 || y0 >= y1; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  // Forced inline, as the whole-tile tests that use it (coverage.h's classifyTiles).
  [[gnu::always_inline]] PixelRect intersect(const PixelRect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
  friend bool operator==(const PixelRect&, const PixelRect&) = default;
};

}  // namespace rast
