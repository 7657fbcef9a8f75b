// Interpolation error in ULPs against the exact reference's double-precision oracle
// (reference/interpolation_error.h explains the two measures, value ULPs and scale ULPs):
// perspective-correct varyings and depth at every covered pixel of random triangles, well-shaped,
// near-degenerate (slivers, sub-pixel) and near the near plane (w down to 1/200 of the other
// vertices', depth near 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/viewport.h"
#include "reference/exact_rasterizer.h"
#include "reference/interpolation_error.h"

namespace rast {
namespace {

constexpr int kSize = 64;
enum class Kind { WellShaped, NearDegenerate, NearPlane };
constexpr const char* kKindNames[] = {"well-shaped", "near-degenerate", "near-plane"};

ShadedVertex<2> clipVertex(double wx, double wy, double w, double zNdc, float u, float v) {
  const double h = kSize / 2.0;
  return {glm::vec4(glm::dvec4((wx - h) / h * w, -(wy - h) / h * w, zNdc * w, w)), {u, v}};
}

std::array<ShadedVertex<2>, 3> randomTriangle(std::mt19937_64& rng, Kind kind) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto position = [&] { return glm::dvec2(-8 + 80 * u(rng), -8 + 80 * u(rng)); };
  std::array<glm::dvec2, 3> p = {position(), position(), position()};
  std::array<double, 3> w, z;
  for (int k = 0; k < 3; ++k) w[k] = 0.5 + 3.5 * u(rng), z[k] = -0.95 + 1.9 * u(rng);
  if (kind == Kind::NearDegenerate) {
    if (rng() % 2) {  // a sliver: the third vertex within 0.3 pixel of the others' segment
      const double s = u(rng);
      const glm::dvec2 d = p[1] - p[0];
      const glm::dvec2 normal = glm::dvec2(-d.y, d.x) / std::max(1e-9, glm::length(d));
      p[2] = p[0] + s * d + (u(rng) - 0.5) * 0.6 * normal;
    } else {  // within a 2-pixel square
      for (int k = 1; k < 3; ++k) p[k] = p[0] + glm::dvec2(2 * u(rng) - 1, 2 * u(rng) - 1);
    }
  } else if (kind == Kind::NearPlane) {
    // One or two vertices just in front of the near plane: small w, window depth 1e-5 .. 1e-3.
    for (int k = 0; k < 1 + int(rng() % 2); ++k) {
      w[k] = 0.005 + 0.015 * u(rng);
      z[k] = -1 + 2 * std::pow(10.0, -3 - 2 * u(rng));
    }
    for (int k = 0; k < 3; ++k)
      if (w[k] > 0.1) w[k] = 1 + 3 * u(rng);
  }
  std::array<ShadedVertex<2>, 3> t;
  for (int k = 0; k < 3; ++k)  // u in [0, 1]; v with a large offset, so relative precision matters
    t[k] = clipVertex(p[k].x, p[k].y, w[k], z[k], float(u(rng)), float(1000.0 + u(rng)));
  return t;
}

// Well-shaped: area at least 40 px^2 and no altitude below a fifth of the longest edge.
bool wellShaped(const std::array<ShadedVertex<2>, 3>& t, PipelineState state) {
  state.viewport = {0, 0, kSize, kSize};
  const ScreenMapping mapping = ScreenMapping::forState(state);
  std::array<reference::WindowPoint, 3> p;
  for (int k = 0; k < 3; ++k) {
    const WindowPosition w = mapping.toWindow(glm::dvec4(t[k].position));
    p[k] = {w.x, w.y};
  }
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, std::hypot(p[(k + 1) % 3].x - p[k].x, p[(k + 1) % 3].y - p[k].y));
  const double area2 = std::abs((p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y));
  return area2 >= 80 && area2 / longest >= 0.2 * longest;
}

// The bound, by measurement (seeded, 1,200 triangles a kind, 24.4 and 16.8; printed below): the
// worst scale-ULP error is 3.10 for depth (near-plane triangles) and 1.78 for the varyings. Why
// about 3: each float rounding errs by at most 2^-24 of its result. Setup rounds at0, ddx and ddy
// to float (together at most 2^-24 S), the evaluation rounds two products and two sums (each
// result at most S): about 3 (2^-24 S) to first order. A varying u = q / r adds the q and r
// planes' errors, 3 (2^-24) (S_q + |u| S_r) / r to first order, and two roundings of values near
// |u|. The assertion allows 4 for both: room for second-order terms and other seeds, none for a
// broken interpolation (screen-linear interpolation of u measures about 10^8 here).
constexpr double kDepthScaleUlpBound = 4.0;
constexpr double kVaryingScaleUlpBound = 4.0;

TEST(InterpolationUlps, PerspectiveVaryingsAndDepthAgainstExactOracle) {
  const uint64_t seed = 0x0171e5a1;
  std::printf("[ seed ] %llu\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  std::array<reference::InterpolationErrors, 3> errors;
  reference::InterpolationErrors floatMode;  // every triangle again in RasterMode::Float
  for (const Kind kind : {Kind::WellShaped, Kind::NearDegenerate, Kind::NearPlane})
    for (int i = 0; i < 1200; ++i) {
      PipelineState state;
      state.format = i % 2 ? FixedPointFormat::d16_8() : FixedPointFormat::d24_4();
      const std::array<ShadedVertex<2>, 3> t = randomTriangle(rng, kind);
      if (kind == Kind::WellShaped && !wellShaped(t, state)) continue;
      reference::InterpolationErrors e;
      const Status s = reference::measureInterpolation(t, state, kSize, kSize, e);
      ASSERT_TRUE(s.isOk()) << s.message();
      ASSERT_FALSE(e.clipped) << "the triangles are made not to need clipping";
      errors[int(kind)].add(e);
      // Float mode interpolates over the float vertices: the same arithmetic, the same bound.
      state.rasterMode = RasterMode::Float;
      reference::InterpolationErrors f;
      ASSERT_TRUE(reference::measureInterpolation(t, state, kSize, kSize, f).isOk());
      floatMode.add(f);
    }
  std::printf("%-16s %-6s %8s %12s %14s\n", "triangles", "value", "pixels", "scale ULPs",
              "value ULPs");
  const char* names[] = {"depth", "u", "v+1000"};
  double affine = 0;
  for (int k = 0; k < 3; ++k) {
    affine = std::max(affine, k == int(Kind::NearDegenerate) ? 0.0 : errors[k].affineScaleUlps);
    for (int j = 0; j < 3; ++j) {
      const reference::ErrorMaximum& w = j == 0 ? errors[k].depth : errors[k].varyings[j - 1];
      std::printf("%-16s %-6s %8llu %12.3f %14.4g\n", kKindNames[k], names[j],
                  (unsigned long long)w.pixels, w.scaleUlps, w.valueUlps);
      EXPECT_GT(w.pixels, 1000u) << kKindNames[k] << ": too few pixels to mean anything";
      EXPECT_LE(w.scaleUlps, j == 0 ? kDepthScaleUlpBound : kVaryingScaleUlpBound)
          << kKindNames[k] << " " << names[j];
    }
  }
  std::printf("float mode, all kinds: depth %.3f, u %.3f, v %.3f scale ULPs over %llu pixels\n",
              floatMode.depth.scaleUlps, floatMode.varyings[0].scaleUlps,
              floatMode.varyings[1].scaleUlps, (unsigned long long)floatMode.depth.pixels);
  EXPECT_LE(floatMode.depth.scaleUlps, kDepthScaleUlpBound);
  EXPECT_LE(floatMode.varyings[0].scaleUlps, kVaryingScaleUlpBound);
  EXPECT_LE(floatMode.varyings[1].scaleUlps, kVaryingScaleUlpBound);
  std::printf("screen-linear u, for contrast: %.4g scale ULPs\n", affine);
  // The measure tells a broken interpolation apart.
  EXPECT_GT(affine, 100 * kVaryingScaleUlpBound);
}

}  // namespace
}  // namespace rast
