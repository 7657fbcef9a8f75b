// Snapping, pixel centres, guard-band clamping and the format limits of rasterizer/fixed_point.h.
#include "rasterizer/fixed_point.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "rasterizer/edge_function.h"

namespace rast {
namespace {

using i128 = __int128;

const FixedPointFormat kFormats[] = {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()};

// Window coordinate (pixels) of a position given in subpixels, possibly fractional. Exact: the
// scale is a power of two and every value used here has few significant bits.
double pixelsOf(double subpixels, FixedPointFormat f) {
  return std::ldexp(subpixels, -f.fractionBits);
}

double below(double x) { return std::nextafter(x, -std::numeric_limits<double>::infinity()); }
double above(double x) { return std::nextafter(x, std::numeric_limits<double>::infinity()); }

TEST(FixedPoint, ExactSubpixelsSnapToThemselves) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    for (int k : {0, 1, -1, 2, -2, 7, -7, 1000, -1000, 123457, -123457}) {
      EXPECT_EQ(snapToSubpixels(pixelsOf(k, f), f), k);
    }
  }
}

TEST(FixedPoint, HalfSubpixelTiesRoundToEven) {
  // Ties must go to the even neighbour, not away from zero or up: a vertex exactly half a subpixel
  // from two grid points has to snap the same way in every path that snaps it, and the rounding
  // that float-to-fixed hardware uses is round-to-nearest-even.
  struct Case {
    double halfSteps;  // the input, in subpixels
    int32_t expected;
  };
  const Case cases[] = {{0.5, 0},
                        {1.5, 2},
                        {2.5, 2},
                        {3.5, 4},
                        {-0.5, 0},
                        {-1.5, -2},
                        {-2.5, -2},
                        {-3.5, -4},
                        {7.5, 8},
                        {8.5, 8},
                        {15.5, 16},
                        {-15.5, -16},
                        {1000000.5, 1000000},
                        {1000001.5, 1000002},
                        {-1000000.5, -1000000},
                        {-1000001.5, -1000002}};
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    for (const Case& c : cases) {
      SCOPED_TRACE(c.halfSteps);
      EXPECT_EQ(snapToSubpixels(pixelsOf(c.halfSteps, f), f), c.expected);
    }
  }
}

TEST(FixedPoint, JustOffTheTieRoundsToTheNearerSubpixel) {
  // One ulp away from a tie there is no tie any more: the nearer subpixel wins whichever is even.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    for (int k : {0, 1, 2, 3, 8, 15, 1000000, 1000001, -1, -2, -3, -16, -1000001}) {
      SCOPED_TRACE(k);
      const double tie = pixelsOf(k + 0.5, f);
      EXPECT_EQ(snapToSubpixels(below(tie), f), k);
      EXPECT_EQ(snapToSubpixels(above(tie), f), k + 1);
    }
  }
}

TEST(FixedPoint, NegationCommutesWithSnapping) {
  // Ties-to-even is symmetric about zero (unlike round-half-up), so a mirrored scene snaps to the
  // mirrored grid positions.
  std::mt19937_64 rng(0xF1CED0);
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    std::uniform_int_distribution<int> halfSteps(-4000000, 4000000);
    std::uniform_real_distribution<double> anywhere(-f.guardBandPixels(), f.guardBandPixels());
    for (int i = 0; i < 2000; ++i) {
      const double x = i % 2 ? pixelsOf(halfSteps(rng) * 0.5, f) : anywhere(rng);
      SCOPED_TRACE(x);
      EXPECT_EQ(snapToSubpixels(-x, f), -snapToSubpixels(x, f));
    }
  }
}

TEST(FixedPoint, PixelCentresSitHalfAPixelIntoThePixel) {
  const FixedPointFormat f24 = FixedPointFormat::d24_4(), f16 = FixedPointFormat::d16_8();
  EXPECT_EQ(pixelCentreSubpixels(0, f24), 8);
  EXPECT_EQ(pixelCentreSubpixels(1, f24), 24);
  EXPECT_EQ(pixelCentreSubpixels(-1, f24), -8);
  EXPECT_EQ(pixelCentreSubpixels(-2, f24), -24);
  EXPECT_EQ(pixelCentreSubpixels(1000, f24), 16008);
  EXPECT_EQ(pixelCentreSubpixels(0, f16), 128);
  EXPECT_EQ(pixelCentreSubpixels(1, f16), 384);
  EXPECT_EQ(pixelCentreSubpixels(-1, f16), -128);
  EXPECT_EQ(pixelCentreSubpixels(-2, f16), -384);
  EXPECT_EQ(pixelCentreSubpixels(1000, f16), 256128);
  // The last pixel inside the guard band still has its centre on the grid and inside the band.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    const int last = int(f.guardBandPixels()) - 1;
    EXPECT_EQ(pixelCentreSubpixels(last, f), f.guardBandSubpixels() - f.subpixelsPerPixel() / 2);
    EXPECT_EQ(pixelCentreSubpixels(-last - 1, f),
              -f.guardBandSubpixels() + f.subpixelsPerPixel() / 2);
  }
}

TEST(FixedPoint, SnappingAPixelCentreGivesPixelCentreSubpixels) {
  // Samples and vertices must agree on where a pixel centre is, or vertices placed on centres
  // would not create the exact ties the fill rule exists for.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    for (int p : {0, 1, 2, 17, -1, -2, -17, 4095, -4096, 16383, -16384}) {
      SCOPED_TRACE(p);
      EXPECT_EQ(snapToSubpixels(p + 0.5, f), pixelCentreSubpixels(p, f));
      EXPECT_EQ(subpixelsToPixels(pixelCentreSubpixels(p, f), f), p + 0.5);
    }
  }
}

TEST(FixedPoint, GuardBandSizes) {
  EXPECT_EQ(FixedPointFormat::d24_4().guardBandSubpixels(), int32_t{1} << 26);
  EXPECT_EQ(FixedPointFormat::d24_4().guardBandPixels(), double(1 << 22));
  EXPECT_EQ(FixedPointFormat::d16_8().guardBandSubpixels(), int32_t{1} << 22);
  EXPECT_EQ(FixedPointFormat::d16_8().guardBandPixels(), 16384.0);
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    EXPECT_EQ(double(f.guardBandSubpixels()), f.guardBandPixels() * f.subpixelsPerPixel());
  }
}

TEST(FixedPoint, ClampsToTheGuardBand) {
  // Clipping leaves vertices inside the guard band only up to a rounding ulp; clamping is what
  // makes |v| <= guardBandSubpixels, the premise of the int64 exactness argument, hold anyway.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    const int32_t g = f.guardBandSubpixels();
    const double gp = f.guardBandPixels();
    EXPECT_EQ(snapToSubpixels(gp, f), g);
    EXPECT_EQ(snapToSubpixels(-gp, f), -g);
    EXPECT_EQ(snapToSubpixels(above(gp), f), g);
    EXPECT_EQ(snapToSubpixels(below(-gp), f), -g);
    EXPECT_EQ(snapToSubpixels(gp + pixelsOf(0.5, f), f), g);  // a tie just outside: still g
    EXPECT_EQ(snapToSubpixels(gp + pixelsOf(1, f), f), g);
    EXPECT_EQ(snapToSubpixels(-gp - pixelsOf(1, f), f), -g);
    EXPECT_EQ(snapToSubpixels(gp + 1000.0, f), g);
    EXPECT_EQ(snapToSubpixels(-gp - 1000.0, f), -g);
    EXPECT_EQ(snapToSubpixels(1e30, f), g);
    EXPECT_EQ(snapToSubpixels(-1e30, f), -g);
    EXPECT_EQ(snapToSubpixels(std::numeric_limits<double>::max(), f), g);
    EXPECT_EQ(snapToSubpixels(std::numeric_limits<double>::lowest(), f), -g);
    // Inside the band nothing is clamped.
    EXPECT_EQ(snapToSubpixels(gp - pixelsOf(1, f), f), g - 1);
    EXPECT_EQ(snapToSubpixels(-gp + pixelsOf(1, f), f), -g + 1);
    EXPECT_EQ(snapToSubpixels(gp - pixelsOf(0.5, f), f), g);      // tie: g is even
    EXPECT_EQ(snapToSubpixels(gp - pixelsOf(1.5, f), f), g - 2);  // tie: g - 2 is even
    EXPECT_EQ(snapToSubpixels(below(gp - pixelsOf(0.5, f)), f), g - 1);
  }
}

TEST(FixedPoint, NamedFormats) {
  EXPECT_EQ(FixedPointFormat::d24_4(), (FixedPointFormat{24, 4}));
  EXPECT_EQ(FixedPointFormat::d16_8(), (FixedPointFormat{16, 8}));
  EXPECT_EQ(FixedPointFormat{}, FixedPointFormat::d24_4());
  EXPECT_EQ(FixedPointFormat::d24_4().name(), "24.4");
  EXPECT_EQ(FixedPointFormat::d16_8().name(), "16.8");
  EXPECT_EQ(FixedPointFormat::d24_4().subpixelsPerPixel(), 16);
  EXPECT_EQ(FixedPointFormat::d16_8().subpixelsPerPixel(), 256);
}

TEST(FixedPoint, WithFractionBitsCoversEveryValidFractionCount) {
  for (int f = 1; f <= FixedPointFormat::kMaxFractionBits; ++f) {
    SCOPED_TRACE(f);
    const FixedPointFormat fmt = FixedPointFormat::withFractionBits(f);
    EXPECT_TRUE(fmt.valid());
    EXPECT_EQ(fmt.fractionBits, f);
    EXPECT_EQ(fmt.subpixelsPerPixel(), 1 << f);
    // 16.8 keeps Direct3D's integer range; every other F uses the full 28 bits.
    EXPECT_EQ(fmt.integerBits, f == 8 ? 16 : 28 - f);
  }
  EXPECT_EQ(FixedPointFormat::withFractionBits(4), FixedPointFormat::d24_4());
  EXPECT_EQ(FixedPointFormat::withFractionBits(8), FixedPointFormat::d16_8());
}

TEST(FixedPoint, ValidMatchesTheStatedLimits) {
  // valid() must accept exactly 1 <= F <= 8, I >= 4, I + F <= 28: outside that the overflow
  // argument in fixed_point.h no longer holds (or F = 0 has no pixel centre on the grid).
  for (int i = -2; i <= 40; ++i) {
    for (int f = -2; f <= 12; ++f) {
      const bool expected = f >= 1 && f <= 8 && i >= 4 && i + f <= 28;
      EXPECT_EQ((FixedPointFormat{i, f}.valid()), expected) << i << "." << f;
    }
  }
  EXPECT_FALSE((FixedPointFormat{24, 5}.valid()));
  EXPECT_FALSE((FixedPointFormat{20, 9}.valid()));
  EXPECT_FALSE((FixedPointFormat{27, 0}.valid()));
  EXPECT_FALSE((FixedPointFormat{3, 8}.valid()));
}

std::vector<FixedPointFormat> allValidFormats() {
  std::vector<FixedPointFormat> out;
  for (int f = 1; f <= FixedPointFormat::kMaxFractionBits; ++f)
    for (int i = 4; i + f <= FixedPointFormat::kMaxTotalBits; ++i) out.push_back({i, f});
  return out;
}

TEST(FixedPoint, GuardBandBoundsOfTheHeaderHold) {
  for (const FixedPointFormat f : allValidFormats()) {
    SCOPED_TRACE(f.name());
    ASSERT_TRUE(f.valid());
    EXPECT_LE(int64_t{f.guardBandSubpixels()}, int64_t{1} << 26);
    // The guard band is half the representable range of an I.F number.
    EXPECT_EQ(int64_t{f.guardBandSubpixels()} * 2,
              int64_t{1} << (f.integerBits + f.fractionBits - 1));
  }
}

TEST(FixedPoint, WorstCaseEdgeFunctionFitsInt64) {
  // E is affine in each of x0, y0, x1, y1, px, py separately, so over a box its extremes are at
  // the box corners: enumerating the 2^6 corner combinations finds the exact worst case. Vertices
  // range over the guard band; samples over the guard band plus one 8x8 tile, because coverage
  // kernels evaluate every sample of a tile that merely touches the bounds.
  for (const FixedPointFormat f : allValidFormats()) {
    SCOPED_TRACE(f.name());
    const int64_t g = f.guardBandSubpixels();
    const int64_t s = g + 8 * int64_t{f.subpixelsPerPixel()};
    i128 worst = 0, worstTileStep = 0, worstClassify = 0;
    for (int m = 0; m < 64; ++m) {
      const auto pick = [&](int bit, int64_t r) { return (m >> bit) & 1 ? r : -r; };
      const SnappedPoint from{int32_t(pick(0, g)), int32_t(pick(1, g))};
      const SnappedPoint to{int32_t(pick(2, g)), int32_t(pick(3, g))};
      const int64_t px = pick(4, s), py = pick(5, s);
      const i128 a = i128(from.y) - to.y, b = i128(to.x) - from.x;
      const bool topLeft = a > 0 || (a == 0 && b > 0);
      const i128 exact = a * (px - from.x) + b * (py - from.y) - (topLeft ? 0 : 1);
      const i128 mag = exact < 0 ? -exact : exact;
      worst = std::max(worst, mag);
      // The tile step of classifyTile: 7 pixels per axis, both axes at once.
      const i128 step = (a < 0 ? -a : a) * 7 * f.subpixelsPerPixel() +
                        (b < 0 ? -b : b) * 7 * f.subpixelsPerPixel();
      worstTileStep = std::max(worstTileStep, step);
      worstClassify = std::max(worstClassify, mag + step);
      // The header's per-term bounds.
      ASSERT_LE(a < 0 ? -a : a, i128(1) << 27);
      ASSERT_LE(b < 0 ? -b : b, i128(1) << 27);
      ASSERT_LE(mag, i128(std::numeric_limits<int64_t>::max()));
      // The library's own int64 evaluation agrees with the exact value (a wrap would not).
      const EdgeFunction e = EdgeFunction::through(from, to);
      ASSERT_EQ(i128(e.a), a);
      ASSERT_EQ(i128(e.b), b);
      ASSERT_EQ(i128(e.at(px, py)), exact);
    }
    // "the four-term sum below 2^55"; in fact |E| is twice a triangle area inside a square of
    // side 2g + 16 px, so it stays near 2^54 at most.
    EXPECT_LT(worst, i128(1) << 55);
    EXPECT_LE(worstTileStep, i128(1) << 39);  // "<= 2^38 per axis"
    EXPECT_LT(worstClassify, i128(std::numeric_limits<int64_t>::max()) / 4);
  }
}

}  // namespace
}  // namespace rast
