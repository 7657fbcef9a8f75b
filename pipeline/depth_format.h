// Depth buffer formats: what a fragment's depth becomes when a format stores it, and how finely a
// perspective projection's depth is resolved by it.
//
// The depth plane always holds floats. A unorm format of n bits stores an integer k in
// [0, 2^n - 1] for the depth k / (2^n - 1); here k is kept as the float nearest to k / (2^n - 1),
// which preserves the integers' order and equality exactly (proof below), so every compare on the
// stored floats is the compare the integers would make, and quantising a stored value again
// returns it unchanged.
//
// Quantisation: k = round(z * (2^n - 1)), to nearest with ties to even, z clamped to [0, 1] first
// (NaN to 0). The product is exact in double (24 bits times at most 24 bits), so k is the exactly
// rounded integer.
//
// Representation (why float(double(k) / N), N = 2^n - 1, is the float nearest to k / N, and why
// distinct k give distinct, equally ordered floats), for n <= 24:
//   * k / N with N odd is a dyadic rational only for k = 0 or k = N, which are exact. For other k
//     it is never a midpoint M = m / 2^j between floats (m < 2^25): |k / N - M| =
//     |k 2^j - m N| / (N 2^j) >= 1 / (N 2^j), which relative to M is >= 1 / (N m) > 2^-49. The
//     double quotient is within 2^-53 relatively, so it lies on the same side of every midpoint as
//     k / N, and rounding it to float gives the float nearest to k / N.
//   * Neighbours k / N and (k + 1) / N differ by 1 / N > 2^-24, while floats in [0, 1] are at
//     most 2^-24 apart; two reals more than one float spacing apart, neither of them a midpoint,
//     round to different floats, and rounding to nearest never reverses an order. So k < k'
//     implies float(k) < float(k'): compares on the floats equal compares on the integers.
#pragma once

#include <cmath>
#include <string_view>

namespace rast {

enum class DepthFormat { Float32, Unorm24, Unorm16 };

constexpr int unormBits(DepthFormat f) {
  return f == DepthFormat::Unorm24 ? 24 : (f == DepthFormat::Unorm16 ? 16 : 0);
}

constexpr std::string_view depthFormatName(DepthFormat f) {
  return f == DepthFormat::Float32 ? "float32" : (f == DepthFormat::Unorm24 ? "unorm24" : "unorm16");
}

// The unorm integer k of a depth (see above).
inline double unormLevel(float z, int bits) {
  const double n = std::ldexp(1.0, bits) - 1.0;
  const double clamped = z > 0.0f ? (z < 1.0f ? double(z) : 1.0) : 0.0;  // NaN -> 0
  return std::nearbyint(clamped * n);
}

// The depth as the format stores it, in the float depth plane.
template <DepthFormat F>
inline float quantizeDepth(float z) {
  if constexpr (F == DepthFormat::Float32) {
    return z;
  } else {
    constexpr int kBits = unormBits(F);
    return float(unormLevel(z, kBits) / (std::ldexp(1.0, kBits) - 1.0));
  }
}

inline float quantizeDepth(DepthFormat f, float z) {
  switch (f) {
    case DepthFormat::Unorm24: return quantizeDepth<DepthFormat::Unorm24>(z);
    case DepthFormat::Unorm16: return quantizeDepth<DepthFormat::Unorm16>(z);
    case DepthFormat::Float32: break;
  }
  return quantizeDepth<DepthFormat::Float32>(z);
}

// ---- Depth resolution of a perspective projection.
//
// With near n and far f, an eye distance d maps (OpenGL's projection followed by the pipeline's
// 0.5 z/w + 0.5) to the window depth
//   standard: z(d) = f (d - n) / ((f - n) d)     (0 at the near plane, 1 at the far plane)
//   reversed: z(d) = n (f - d) / ((f - n) d)     (1 at the near plane, 0 at the far plane)
// and in both |dz/dd| = f n / ((f - n) d^2).
//
// Fragments reach the merge stage as float depths and are then quantised, so two depths z1 < z2
// are surely told apart when z2 - z1 exceeds the format's step plus one float spacing at z (the
// float rounding of each depth moves it by at most half a spacing):
//   unorm n: 1 / (2^n - 1) + ulp(z);   float32: ulp(z)   (the spacing of floats just above z).
// The resolution at distance d is that depth gap divided by |dz/dd|: the smallest separation
// along the view direction that is resolved for sure, to first order in the separation. Closer
// separations may still resolve by luck of where the quantisation steps fall.
struct PerspectiveDepth {
  double nearPlane = 0.1, farPlane = 100.0;
  bool reversed = false;

  double windowDepth(double d) const {
    const double f = farPlane, n = nearPlane;
    return reversed ? n * (f - d) / ((f - n) * d) : f * (d - n) / ((f - n) * d);
  }
  double depthPerDistance(double d) const {
    return farPlane * nearPlane / ((farPlane - nearPlane) * d * d);
  }
  // The eye distance whose window depth is z (the inverse of windowDepth).
  double distanceAt(double z) const {
    const double f = farPlane, n = nearPlane;
    return reversed ? n * f / (n + z * (f - n)) : f * n / (f - z * (f - n));
  }
};

// Spacing of floats just above z >= 0 (for z in [2^e, 2^(e+1)): 2^(e-23)).
inline double floatSpacingAbove(double z) {
  const float f = float(z);
  return double(std::nextafter(f, 2.0f)) - double(f);
}

// The smallest depth gap the format resolves for sure at window depth z.
inline double depthGapResolved(DepthFormat format, double z) {
  const double floatStep = floatSpacingAbove(z);
  if (format == DepthFormat::Float32) return floatStep;
  return 1.0 / (std::ldexp(1.0, unormBits(format)) - 1.0) + floatStep;
}

// The smallest separation at eye distance d that the format resolves for sure (see above).
inline double depthResolution(DepthFormat format, const PerspectiveDepth& projection, double d) {
  return depthGapResolved(format, projection.windowDepth(d)) / projection.depthPerDistance(d);
}

}  // namespace rast
