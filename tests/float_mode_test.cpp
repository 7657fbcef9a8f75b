// Float mode (RasterMode::Float, rasterizer/float_coverage.h): the pipeline covers exactly what the
// naive rule defines, and on the watertightness cases it shows the gaps and double hits that the
// fixed-point mode never has.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/front_end.h"
#include "reference/exact_rasterizer.h"
#include "reference/watertight_cases.h"
#include "tests/coverage_cases.h"

namespace rast {
namespace {

using reference::WindowPoint;
using reference::WindowTriangle;
using test_support::DrawnCoverage;
using test_support::drawWindowTriangles;
using test_support::TriangleHashShader;

// The naive rule as float_coverage.h states it, sample by sample.
bool naiveCovers(const WindowTriangle& t, int px, int py) {
  std::array<float, 3> x, y;
  for (int i = 0; i < 3; ++i) x[i] = float(t[i].x), y[i] = float(t[i].y);
  const float area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const double areaInDouble = (double(x[1]) - x[0]) * (double(y[2]) - y[0]) -
                              (double(x[2]) - x[0]) * (double(y[1]) - y[0]);
  if (area == 0 || areaInDouble == 0) return false;
  if (area < 0) std::swap(x[1], x[2]), std::swap(y[1], y[2]);
  const float sx = float(px) + 0.5f, sy = float(py) + 0.5f;
  if (sx < std::min({x[0], x[1], x[2]}) || sx > std::max({x[0], x[1], x[2]}) ||
      sy < std::min({y[0], y[1], y[2]}) || sy > std::max({y[0], y[1], y[2]}))
    return false;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const float a = y[i] - y[j], b = x[j] - x[i];
    const float c = -(a * x[i] + b * y[i]);
    if (!((a * sx + b * sy) + c >= 0)) return false;
  }
  return true;
}

// The tile corner tests (binning and raster) and the masks must not change a single sample of
// the per-sample rule.
TEST(FloatMode, CoverageEqualsTheNaiveRuleSampleBySample) {
  const uint64_t seed = 0xf10a7001;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  constexpr int W = 88, H = 72;
  uint64_t covered = 0;
  for (int batch = 0; batch < 8; ++batch) {
    std::vector<WindowTriangle> triangles;
    // The last batch is ten chunks of triangles: enough for the front end to bin each chunk while
    // setting it up (binWhileSettingUp, draw.h) on machines of up to five threads, with the
    // triangles' float edges; the others are binned in a pass of their own.
    const int count = batch == 7 ? 10 * int(SetupTriangles<0>::kInputChunk) : 300;
    for (int i = 0; i < count; ++i)
      triangles.push_back(test_support::randomTriangle(rng, FixedPointFormat::d16_8(), W, H));
    const DrawnCoverage drawn =
        drawWindowTriangles(triangles, W, H, FixedPointFormat::d16_8(), RasterMode::Float);
    ASSERT_TRUE(drawn.status.isOk()) << drawn.status.message();
    std::vector<uint32_t> counts(size_t(W) * H, 0);
    std::vector<uint64_t> hashes(size_t(W) * H, 0);
    for (size_t i = 0; i < triangles.size(); ++i) {
      // Pixels around the triangle's bounding box, clamped to the image.
      const WindowTriangle& t = triangles[i];
      auto range = [](double lo, double hi, int size) {
        return std::pair<int, int>(int(std::clamp(std::floor(lo) - 1, 0.0, double(size))),
                                   int(std::clamp(std::ceil(hi) + 1, 0.0, double(size))));
      };
      const auto [x0, x1] = range(std::min({t[0].x, t[1].x, t[2].x}), std::max({t[0].x, t[1].x, t[2].x}), W);
      const auto [y0, y1] = range(std::min({t[0].y, t[1].y, t[2].y}), std::max({t[0].y, t[1].y, t[2].y}), H);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
          if (naiveCovers(t, x, y)) {
            ++counts[size_t(y) * W + x];
            hashes[size_t(y) * W + x] += TriangleHashShader::hashTriangle(i);
          }
    }
    int wrong = 0;
    for (size_t i = 0; i < counts.size(); ++i) {
      covered += counts[i];
      if ((drawn.counts[i] != counts[i] || drawn.hashes[i] != hashes[i]) && ++wrong <= 5)
        ADD_FAILURE() << "batch " << batch << ": pixel (" << i % W << ", " << i / W << ") count "
                      << drawn.counts[i] << ", naive rule " << counts[i];
    }
    ASSERT_EQ(wrong, 0) << "batch " << batch;
  }
  EXPECT_GT(covered, 100000u);
}

// ---------------------------------------------------------------------------------------------
// The fan and grid cases of tests/watertight_test.cpp (same generators, same seeds), drawn in both
// modes, at the origin and 4096 pixels to its right, where float edge constants c = -(a x + b y)
// round away bits that fixed point keeps.

struct CaseResult {
  reference::WatertightViolations fixedPoint, floatMode;
  bool floatEqualsClosedTriangles = true;  // float coverage = exact closed-triangle coverage
};

CaseResult runCase(const reference::Mesh2D& m, FixedPointFormat format, int offset) {
  constexpr int kSize = 64;
  const int width = offset + kSize;
  const int64_t unit = format.subpixelsPerPixel();
  reference::Mesh2D shifted = m;
  for (reference::SubPoint& p : shifted.vertices) p.x += int64_t(offset) * unit;
  std::vector<WindowTriangle> triangles;
  for (size_t t = 0; t + 2 < shifted.indices.size(); t += 3) {
    WindowTriangle w;
    for (int k = 0; k < 3; ++k) {
      const reference::SubPoint p = shifted.vertices[shifted.indices[t + k]];
      w[k] = {double(p.x) / double(unit), double(p.y) / double(unit)};  // exact in float here
    }
    triangles.push_back(w);
  }
  const std::vector<uint8_t> inside = reference::strictlyInsideUnion(shifted, unit, width, kSize);
  CaseResult r;
  const DrawnCoverage fixed = drawWindowTriangles(triangles, width, kSize, format, RasterMode::FixedPoint);
  const DrawnCoverage naive = drawWindowTriangles(triangles, width, kSize, format, RasterMode::Float);
  EXPECT_TRUE(fixed.status.isOk() && naive.status.isOk());
  r.fixedPoint = reference::countViolations(inside, fixed.counts);
  r.floatMode = reference::countViolations(inside, naive.counts);
  const reference::CoverageCounts closed = reference::rasterizeCounts(
      triangles, width, kSize, {false, format, reference::SampleRule::ClosedTriangle});
  EXPECT_EQ(closed.undecidable, 0u);
  r.floatEqualsClosedTriangles = closed.counts == naive.counts;
  return r;
}

TEST(FloatMode, FansAndGridsReportGapsAndDoubleHits) {
  std::printf("%-6s %-6s %-5s %9s %12s %12s %14s\n", "format", "offset", "case", "interior",
              "float gaps", "float double", "= closed rule");
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    for (const int offset : {0, 4096}) {
      const int64_t unit = format.subpixelsPerPixel();
      for (const bool fans : {true, false}) {
        // The seeds and the sequence of draws of watertight_test.cpp's FansCoverUnionOnce and
        // GridsCoverUnionOnce.
        std::mt19937_64 rng(fans ? 0xfa70000 + format.fractionBits : 0x961d0000 + format.fractionBits);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        reference::WatertightViolations fixedSum, floatSum;
        int floatExact = 0;
        for (int iter = 0; iter < 40; ++iter) {
          reference::Mesh2D m;
          if (fans) {
            m = reference::randomFan(rng, unit, 64, 64);
          } else {
            const double cell = iter % 4 == 0 ? 0.3 + u(rng) : 2.0 + 10.0 * u(rng);
            m = reference::randomGrid(rng, unit, 64, 64, iter % 5 != 0, cell);
          }
          const CaseResult r = runCase(m, format, offset);
          fixedSum.gaps += r.fixedPoint.gaps;
          fixedSum.doubleHits += r.fixedPoint.doubleHits;
          floatSum.interior += r.floatMode.interior;
          floatSum.gaps += r.floatMode.gaps;
          floatSum.doubleHits += r.floatMode.doubleHits;
          floatExact += r.floatEqualsClosedTriangles;
        }
        const std::string what = format.name() + " offset " + std::to_string(offset) +
                                 (fans ? " fans" : " grids");
        // Certain: fixed point is watertight.
        EXPECT_EQ(fixedSum.gaps, 0u) << what;
        EXPECT_EQ(fixedSum.doubleHits, 0u) << what;
        // Certain: at 24.4 near the origin every float operation of the naive rule is exact.
        // Coordinates are multiples of 1/16 within (-2^7, 2^7) and edges shorter than 2^6
        // pixels, so a and b are integers below 2^10 in 1/16 units, a x and c below 2^22 in
        // 1/256 units, and every partial sum of E below 2^16 pixels^2, 2^24 in 1/256 units: all
        // exact in float's 24 bits. So float mode covers the closed triangles exactly: no gap,
        // and a double hit at each sample on a shared edge.
        if (format == FixedPointFormat::d24_4() && offset == 0) {
          EXPECT_EQ(floatExact, 40) << what;
          EXPECT_EQ(floatSum.gaps, 0u) << what;
        }
        std::printf("%-6s %-6d %-5s %9llu %12llu %12llu %11d/40\n", format.name().c_str(), offset,
                    fans ? "fans" : "grids", (unsigned long long)floatSum.interior,
                    (unsigned long long)floatSum.gaps, (unsigned long long)floatSum.doubleHits,
                    floatExact);
      }
    }
  }
}

}  // namespace
}  // namespace rast
