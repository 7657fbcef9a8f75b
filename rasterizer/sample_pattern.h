// Where a pixel's coverage samples lie: its centre without MSAA, Direct3D's standard patterns for
// 4 and 8 samples. Offsets are in 1/16 pixel from the centre, y down (Direct3D's convention too).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>

#include "rasterizer/fixed_point.h"

namespace rast {

inline constexpr int kMaxSamples = 8;

struct SamplePattern {
  int count = 1;
  std::array<std::array<int8_t, 2>, kMaxSamples> offset16{};  // (x, y) in 1/16 pixel

  // An offset in subpixels of `format`. Exact: 1/16 pixel is a whole number of subpixels when
  // the format has at least 4 fraction bits, which validateDraw requires for MSAA.
  int32_t offsetX(int s, FixedPointFormat f) const { return scale(offset16[s][0], f); }
  int32_t offsetY(int s, FixedPointFormat f) const { return scale(offset16[s][1], f); }
  // Offsets in pixels, exact in float.
  float offsetXPixels(int s) const { return float(offset16[s][0]) / 16.0f; }
  float offsetYPixels(int s) const { return float(offset16[s][1]) / 16.0f; }

  // The largest |offset| on either axis, in subpixels: how far samples reach beyond the centre.
  int32_t reach(FixedPointFormat f) const {
    int r = 0;
    for (int s = 0; s < count; ++s)
      r = std::max({r, std::abs(int(offset16[s][0])), std::abs(int(offset16[s][1]))});
    return scale(int8_t(r), f);
  }

  static constexpr bool supported(int count) { return count == 1 || count == 4 || count == 8; }
  static SamplePattern forCount(int count) {
    if (count == 4) return {4, {{{-2, -6}, {6, -2}, {-6, 2}, {2, 6}}}};
    if (count == 8)
      return {8, {{{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}}}};
    return {};
  }

 private:
  static int32_t scale(int8_t v, FixedPointFormat f) {
    return f.fractionBits >= 4 ? int32_t(v) * (int32_t{1} << (f.fractionBits - 4)) : 0;
  }
};

}  // namespace rast
