// Fixed-point window coordinates: the format, its limits, and snapping.
//
// A snapped coordinate is a signed integer count of 1/2^F pixel steps ("subpixels"). A format is
// named I.F: I integer bits (sign included) and F fraction bits, stored in an int32_t.
//
// Bit-exact argument (relied on by EdgeFunction and every coverage kernel):
//   * Valid formats have 1 <= F <= 8 and I + F <= 28.
//   * The guard band is |window coordinate| <= 2^(I-2) pixels, half the representable range, so
//     every snapped coordinate satisfies |v| <= 2^(I+F-2) <= 2^26 subpixels (clipping enforces it;
//     the viewport must lie inside the guard band, so sample positions obey the same bound).
//   * Edge coefficients are vertex differences: |a|, |b| <= 2^(I+F-1) <= 2^27.
//   * E(x, y) = a*x + b*y + c with c = -(a*x0 + b*y0): each product is below 2^53 in magnitude and
//     the four-term sum below 2^55, so int64_t evaluates every edge function exactly. An 8x8 tile
//     step adds at most 8 * 2^F * 2^27 <= 2^38 per axis: also exact.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

namespace rast {

struct FixedPointFormat {
  int integerBits = 24;
  int fractionBits = 4;

  static constexpr int kMaxTotalBits = 28;
  static constexpr int kMaxFractionBits = 8;

  // The default (24.4) and the Direct3D 11 class (16.8) formats.
  static constexpr FixedPointFormat d24_4() { return {24, 4}; }
  static constexpr FixedPointFormat d16_8() { return {16, 8}; }
  // The format with F fraction bits and the integer bits that keep I + F = 28 (F=4 -> 24.4);
  // 16.8 keeps Direct3D's narrower integer range, so it is named explicitly.
  static constexpr FixedPointFormat withFractionBits(int f) {
    return f == 8 ? d16_8() : FixedPointFormat{kMaxTotalBits - f, f};
  }

  constexpr bool valid() const {
    return fractionBits >= 1 && fractionBits <= kMaxFractionBits && integerBits >= 4 &&
           integerBits + fractionBits <= kMaxTotalBits;
  }
  constexpr int32_t subpixelsPerPixel() const { return int32_t{1} << fractionBits; }
  // Largest |window coordinate| in pixels that clipping lets through.
  constexpr double guardBandPixels() const { return double(int64_t{1} << (integerBits - 2)); }
  constexpr int32_t guardBandSubpixels() const {
    return int32_t{1} << (integerBits + fractionBits - 2);
  }
  std::string name() const { return std::to_string(integerBits) + "." + std::to_string(fractionBits); }

  friend constexpr bool operator==(FixedPointFormat, FixedPointFormat) = default;
};

// Snaps a window coordinate (pixels) to the nearest subpixel, ties to even: the IEEE default
// rounding of std::nearbyint, the same rule as hardware float-to-fixed conversion. The input must
// be finite; values beyond the guard band (possible only by a rounding ulp after clipping) are
// clamped so the bound in the header comment always holds.
inline int32_t snapToSubpixels(double windowCoordinate, FixedPointFormat format) {
  // Scaling by 2^F is exact (a power of two), and clamping to the integer limit before rounding
  // gives what clamping after would.
  const double scaled = windowCoordinate * double(format.subpixelsPerPixel());
  const double limit = format.guardBandSubpixels();
  const double clamped = scaled < -limit ? -limit : (scaled > limit ? limit : scaled);
  // |clamped| <= 2^26: adding and removing 1.5 * 2^52 leaves no fraction bits, so the first sum
  // rounds to an integer in the current (default: nearest, ties to even) mode, as nearbyint does,
  // without a library call.
  const double rounded = (clamped + 0x1.8p52) - 0x1.8p52;
  return int32_t(rounded);
}

// Position of the centre of pixel `p` on the subpixel grid: p + 1/2 pixel.
inline int64_t pixelCentreSubpixels(int p, FixedPointFormat format) {
  return (int64_t(p) << format.fractionBits) + (int64_t{1} << (format.fractionBits - 1));
}

// Exact: |v| < 2^53 converts exactly, and scaling by 2^-F (itself exact in double) only moves
// the exponent. A multiply, not a divide by 2^F (the same value): setup does six per triangle,
// and the divider's latency showed in its profile.
inline double subpixelsToPixels(int64_t v, FixedPointFormat format) {
  const double pixelsPerSubpixel = std::bit_cast<double>(uint64_t(1023 - format.fractionBits) << 52);
  return double(v) * pixelsPerSubpixel;  // 2^-F, built from its exponent bits
}

}  // namespace rast
