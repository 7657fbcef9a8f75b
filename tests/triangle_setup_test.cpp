// setupCoverage: winding, double area, zero-area rejection, bounds and their clipping.
#include "rasterizer/triangle_setup.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "rasterizer/coverage.h"
#include "rasterizer/edge_function.h"
#include "rasterizer/fixed_point.h"

namespace rast {
namespace {

using Tri = std::array<SnappedPoint, 3>;

const FixedPointFormat kF24 = FixedPointFormat::d24_4();
const FixedPointFormat kF16 = FixedPointFormat::d16_8();
const FixedPointFormat kFormats[] = {kF24, kF16};
const PixelRect kWideClip{-1000, -1000, 1000, 1000};

// Snaps a triangle given in pixels.
Tri snapped(double x0, double y0, double x1, double y1, double x2, double y2, FixedPointFormat f) {
  return {SnappedPoint{snapToSubpixels(x0, f), snapToSubpixels(y0, f)},
          SnappedPoint{snapToSubpixels(x1, f), snapToSubpixels(y1, f)},
          SnappedPoint{snapToSubpixels(x2, f), snapToSubpixels(y2, f)}};
}

Tri reversed(const Tri& t) { return {t[0], t[2], t[1]}; }
Tri rotated(const Tri& t) { return {t[1], t[2], t[0]}; }

TEST(TriangleSetup, WindingIsClockwiseOnScreenWithYDown) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    // Top-left, top-right, bottom-left: clockwise as seen on a y-down screen.
    const Tri cw = snapped(0, 0, 4, 0, 0, 4, f);
    CoverageSetup s;
    ASSERT_EQ(setupCoverage(cw, kWideClip, f, s), SetupOutcome::Accepted);
    EXPECT_TRUE(s.clockwiseOnScreen);
    ASSERT_EQ(setupCoverage(rotated(cw), kWideClip, f, s), SetupOutcome::Accepted);
    EXPECT_TRUE(s.clockwiseOnScreen);  // rotating the order keeps the winding
    ASSERT_EQ(setupCoverage(rotated(rotated(cw)), kWideClip, f, s), SetupOutcome::Accepted);
    EXPECT_TRUE(s.clockwiseOnScreen);
    ASSERT_EQ(setupCoverage(reversed(cw), kWideClip, f, s), SetupOutcome::Accepted);
    EXPECT_FALSE(s.clockwiseOnScreen);
    ASSERT_EQ(setupCoverage(rotated(reversed(cw)), kWideClip, f, s), SetupOutcome::Accepted);
    EXPECT_FALSE(s.clockwiseOnScreen);
    // A triangle pointing up: bottom-left, apex, bottom-right is clockwise on screen too.
    ASSERT_EQ(setupCoverage(snapped(0, 4, 2, 0, 4, 4, f), kWideClip, f, s), SetupOutcome::Accepted);
    EXPECT_TRUE(s.clockwiseOnScreen);
    ASSERT_EQ(setupCoverage(snapped(0, 4, 4, 4, 2, 0, f), kWideClip, f, s), SetupOutcome::Accepted);
    EXPECT_FALSE(s.clockwiseOnScreen);
  }
}

TEST(TriangleSetup, EdgesArePositiveInsideForBothWindings) {
  // The kernels test E >= 0, so setup must orient the edges towards the interior whatever the
  // submission order; the vertices themselves then lie on the zero line of their two edges.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    const Tri cw = snapped(1, 1, 9, 2, 3, 8, f);
    for (const Tri& t : {cw, rotated(cw), reversed(cw), rotated(reversed(cw))}) {
      CoverageSetup s;
      ASSERT_EQ(setupCoverage(t, kWideClip, f, s), SetupOutcome::Accepted);
      // (4, 4) pixels is strictly inside; (0, 0) and (10, 10) strictly outside.
      const int64_t in = 4 * f.subpixelsPerPixel(), out0 = 0, out1 = 10 * f.subpixelsPerPixel();
      for (const EdgeFunction& e : s.edges) EXPECT_GT(e.at(in, in), 0);
      EXPECT_TRUE(s.edges[0].at(out0, out0) < 0 || s.edges[1].at(out0, out0) < 0 ||
                  s.edges[2].at(out0, out0) < 0);
      EXPECT_TRUE(s.edges[0].at(out1, out1) < 0 || s.edges[1].at(out1, out1) < 0 ||
                  s.edges[2].at(out1, out1) < 0);
      // Edge i runs from vertex i to vertex i+1 of the (possibly reordered) triangle, so each
      // vertex is on two edges and strictly inside the third.
      for (const SnappedPoint& v : t) {
        int onEdge = 0;
        for (const EdgeFunction& e : s.edges) {
          const int64_t value = e.at(v.x, v.y);
          EXPECT_GE(value, -1);  // on the line, E is 0 or the -1 fill-rule bias
          onEdge += value <= 0;
        }
        EXPECT_EQ(onEdge, 2);
      }
    }
  }
}

TEST(TriangleSetup, DoubleAreaIsExactAndPositive) {
  CoverageSetup s;
  // Legs of 4 and 4 pixels: area 8 px^2, double area 16 px^2 = 16 * 16^2 subpixels^2 in 24.4.
  ASSERT_EQ(setupCoverage(snapped(0, 0, 4, 0, 0, 4, kF24), kWideClip, kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.doubleArea, 16 * 256);
  ASSERT_EQ(setupCoverage(snapped(0, 0, 0, 4, 4, 0, kF24), kWideClip, kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.doubleArea, 16 * 256);
  // The same in 16.8: 16 * 256^2.
  ASSERT_EQ(setupCoverage(snapped(0, 0, 4, 0, 0, 4, kF16), kWideClip, kF16, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.doubleArea, 16 * 65536);
  // The smallest triangle there is: legs of one subpixel.
  ASSERT_EQ(setupCoverage({SnappedPoint{8, 8}, SnappedPoint{9, 8}, SnappedPoint{8, 9}}, kWideClip,
                          kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.doubleArea, 1);
  // A general triangle: |(9-1)(8-1) - (3-1)(2-1)| * 256 = 54 * 256.
  ASSERT_EQ(setupCoverage(snapped(1, 1, 9, 2, 3, 8, kF24), kWideClip, kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.doubleArea, 54 * 256);
  ASSERT_EQ(setupCoverage(snapped(1, 1, 3, 8, 9, 2, kF24), kWideClip, kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.doubleArea, 54 * 256);
}

TEST(TriangleSetup, DoubleAreaAtTheGuardBandCorners) {
  // The largest triangles in the guard band: half its square, 2g * 2g = 2^54 subpixels^2 in 24.4,
  // well inside int64.
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    const int32_t g = f.guardBandSubpixels();
    const int gp = int(f.guardBandPixels());
    const Tri t{SnappedPoint{-g, -g}, SnappedPoint{g, -g}, SnappedPoint{-g, g}};
    CoverageSetup s;
    ASSERT_EQ(setupCoverage(t, {-gp, -gp, gp, gp}, f, s), SetupOutcome::Accepted);
    EXPECT_EQ(s.doubleArea, 4 * int64_t{g} * g);
    EXPECT_TRUE(s.clockwiseOnScreen);
    // Pixel centres from -gp + 0.5 to gp - 0.5 on each axis lie in the closed box.
    EXPECT_EQ(s.bounds, (PixelRect{-gp, -gp, gp, gp}));
    ASSERT_EQ(setupCoverage(reversed(t), {-gp, -gp, gp, gp}, f, s), SetupOutcome::Accepted);
    EXPECT_EQ(s.doubleArea, 4 * int64_t{g} * g);
    EXPECT_FALSE(s.clockwiseOnScreen);
  }
}

TEST(TriangleSetup, ZeroAreaForCollinearSnappedVertices) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    CoverageSetup s;
    EXPECT_EQ(setupCoverage(snapped(1, 1, 1, 1, 1, 1, f), kWideClip, f, s), SetupOutcome::ZeroArea);
    EXPECT_EQ(setupCoverage(snapped(1, 1, 5, 1, 1, 1, f), kWideClip, f, s), SetupOutcome::ZeroArea);
    EXPECT_EQ(setupCoverage(snapped(0, 0, 3, 3, 7, 7, f), kWideClip, f, s), SetupOutcome::ZeroArea);
    EXPECT_EQ(setupCoverage(snapped(0, 0, 8, 4, -2, -1, f), kWideClip, f, s),
              SetupOutcome::ZeroArea);
    EXPECT_EQ(setupCoverage(snapped(2, -5, 2, 7, 2, 0.5, f), kWideClip, f, s),
              SetupOutcome::ZeroArea);
    // Collinearity is decided after snapping: 0.001 pixel is below half a subpixel in both
    // formats, so the middle vertex snaps onto the line.
    EXPECT_EQ(setupCoverage(snapped(0, 0, 10, 0.001, 20, 0, f), kWideClip, f, s),
              SetupOutcome::ZeroArea);
    // ... and vertices collinear before snapping need not be after: (1, 1/3) is not on the grid
    // and snaps off the line y = x / 3.
    EXPECT_EQ(setupCoverage(snapped(0, 0, 1, 1.0 / 3.0, 3, 1, f), kWideClip, f, s),
              SetupOutcome::Accepted);
    // One subpixel off the line is not degenerate.
    const double d = std::ldexp(1.0, -f.fractionBits);
    EXPECT_EQ(setupCoverage(snapped(0, 0, 3, 3 + d, 7, 7, f), kWideClip, f, s),
              SetupOutcome::Accepted);
    EXPECT_EQ(s.doubleArea, 7 * f.subpixelsPerPixel());  // |3 * 7 - (3 + d) * 7| in subpixels^2
    // ZeroArea wins even where the box holds no sample or lies outside the clip.
    EXPECT_EQ(setupCoverage(snapped(500, 500, 600, 600, 700, 700, f), {0, 0, 8, 8}, f, s),
              SetupOutcome::ZeroArea);
  }
}

TEST(TriangleSetup, BoundsHoldThePixelCentresOfTheClosedBox) {
  CoverageSetup s;
  // Vertices on pixel centres: those centres are on the triangle, so their pixels are included.
  ASSERT_EQ(setupCoverage(snapped(0.5, 0.5, 3.5, 0.5, 0.5, 3.5, kF24), kWideClip, kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{0, 0, 4, 4}));
  // One subpixel inside on each side: the extreme centres drop out.
  const double d = 1.0 / 16;
  ASSERT_EQ(setupCoverage(snapped(0.5 + d, 0.5 + d, 3.5 - d, 0.5 + d, 0.5 + d, 3.5 - d, kF24),
                          kWideClip, kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{1, 1, 3, 3}));
  // One subpixel outside: nothing changes.
  ASSERT_EQ(setupCoverage(snapped(0.5 - d, 0.5 - d, 3.5 + d, 0.5 - d, 0.5 - d, 3.5 + d, kF24),
                          kWideClip, kF24, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{0, 0, 4, 4}));
  // Negative coordinates: from -3.1875 px the first centre is -2.5 (pixel -3); up to -0.5625 px
  // the last is -1.5 (pixel -2), since the centre -0.5 of pixel -1 lies beyond.
  ASSERT_EQ(
      setupCoverage(snapped(-3.1875, -7.5, -0.5625, -7.5, -3.1875, -0.5, kF24), kWideClip, kF24, s),
      SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{-3, -8, -1, 0}));
  // 16.8: a vertex 1/256 px left of the centre of pixel 5 still includes pixel 5.
  ASSERT_EQ(setupCoverage(snapped(5.5 - 1.0 / 256, 2, 9, 2, 9, 6, kF16), kWideClip, kF16, s),
            SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{5, 2, 9, 6}));
}

TEST(TriangleSetup, BoundsAreClippedToTheClipRect) {
  const Tri t = snapped(-20, -20, 60, -20, -20, 60, kF24);
  CoverageSetup s;
  ASSERT_EQ(setupCoverage(t, {0, 0, 16, 16}, kF24, s), SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{0, 0, 16, 16}));
  ASSERT_EQ(setupCoverage(t, {3, 5, 7, 11}, kF24, s), SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{3, 5, 7, 11}));
  // A clip rect reaching past the triangle keeps the triangle's own box on that side: centres
  // -20 + 0.5 ... 59.5 => pixels [-20, 60).
  ASSERT_EQ(setupCoverage(t, {-100, 10, 100, 12}, kF24, s), SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{-20, 10, 60, 12}));
  // Nothing samples outside the clipped bounds, even where the triangle covers them.
  ASSERT_EQ(setupCoverage(t, {3, 5, 7, 11}, kF24, s), SetupOutcome::Accepted);
  EXPECT_EQ(coverageScalar(s.edges, s.bounds, 0, 0, kF24), rectMask({3, 5, 7, 11}, 0, 0));
  EXPECT_EQ(coverageScalar(s.edges, s.bounds, 0, 1, kF24), rectMask({3, 5, 7, 11}, 0, 1));
  EXPECT_EQ(coverageScalar(s.edges, s.bounds, 1, 0, kF24), 0u);
  // A clip rect that misses the triangle's box.
  EXPECT_EQ(setupCoverage(t, {60, 0, 80, 10}, kF24, s), SetupOutcome::NoSamples);
  EXPECT_EQ(setupCoverage(t, {0, 60, 10, 80}, kF24, s), SetupOutcome::NoSamples);
  // Touching: pixel 59 (centre 59.5) is in the box, so a clip starting at 59 keeps one column.
  ASSERT_EQ(setupCoverage(t, {59, -30, 80, 80}, kF24, s), SetupOutcome::Accepted);
  EXPECT_EQ(s.bounds, (PixelRect{59, -20, 60, 60}));
  // An empty clip rect.
  EXPECT_EQ(setupCoverage(t, {5, 5, 5, 9}, kF24, s), SetupOutcome::NoSamples);
}

TEST(TriangleSetup, NoSamplesForTrianglesBetweenPixelCentres) {
  for (const FixedPointFormat f : kFormats) {
    SCOPED_TRACE(f.name());
    CoverageSetup s;
    // Inside the square of centres (0.5, 0.5)-(1.5, 1.5), touching none.
    EXPECT_EQ(setupCoverage(snapped(0.6, 0.6, 1.4, 0.6, 0.6, 1.4, f), kWideClip, f, s),
              SetupOutcome::NoSamples);
    // Long but thin, between the rows of centres y = 0.5 and y = 1.5.
    EXPECT_EQ(setupCoverage(snapped(-50, 0.75, 50, 0.75, 0, 1.25, f), kWideClip, f, s),
              SetupOutcome::NoSamples);
    // Tall but thin, between the columns x = 2.5 and x = 3.5, reaching negative y.
    EXPECT_EQ(setupCoverage(snapped(2.55, -40, 3.45, -40, 3, 30, f), kWideClip, f, s),
              SetupOutcome::NoSamples);
    // Reaching a centre with a vertex is enough for a non-empty box.
    ASSERT_EQ(setupCoverage(snapped(0.5, 0.5, 1.4, 0.5, 0.5, 1.4, f), kWideClip, f, s),
              SetupOutcome::Accepted);
    EXPECT_EQ(s.bounds, (PixelRect{0, 0, 1, 1}));
  }
}

}  // namespace
}  // namespace rast
