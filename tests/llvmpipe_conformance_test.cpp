// Conformance with Mesa llvmpipe: window-space triangles in 16.8 fixed point, each in its own
// cell of a 1024x1024 image, drawn by llvmpipe (peer/llvmpipe_coverage.h) and by our pipeline;
// the count images must be equal pixel for pixel. llvmpipe's framebuffer has GL's bottom-left
// origin: a vertex at our (x, y) goes to it at (x, 1024 - y), its image is read back with the
// rows reversed, and our pipeline runs with FillRule::BottomLeft, which is llvmpipe's tie rule
// seen that way (README, "Conformance with llvmpipe"). Built when EGL and OpenGL are found.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "peer/llvmpipe_coverage.h"
#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

constexpr int kSize = 1024;

// How a batch places its vertices, inside a cell of `cell` pixels; every value is exact in
// float and reaches llvmpipe unchanged.
enum class Placement {
  SubpixelGrid,      // 1/256: snapping changes nothing, only the fill rule matters
  HalfSubpixelGrid,  // 1/512: half the coordinates are ties for snapping
  FineGrid,          // 1/4096: general rounding to the subpixel grid
  PixelCentres,      // vertices on samples: edges through samples, ties everywhere
  HalfPixelGrid,     // 1/2: edges through samples, horizontal and vertical ones through rows
  SampleRowEdge,     // two vertices on one sample row or column, the third anywhere (1/512)
  TiesNearSamples,   // a sample +-1/512 or +-3/512: snapping ties next to samples
};
constexpr int kPlacements = 7;

std::vector<glm::vec2> cellTriangles(std::mt19937_64& rng, Placement placement, int cell,
                                     int count) {
  std::vector<glm::vec2> v;
  const int perRow = kSize / cell;
  auto grid = [&](int bits) { return double(rng() % (uint64_t(cell) << bits)) / double(1 << bits); };
  auto centre = [&] { return double(rng() % cell) + 0.5; };
  auto nearSample = [&] { return centre() + (double(int(rng() % 4)) - 1.5) / 256.0; };
  for (int t = 0; t < count; ++t) {
    const double ox = (t % perRow) * cell, oy = (t / perRow) * cell;
    std::array<glm::dvec2, 3> p;
    for (glm::dvec2& q : p) {
      switch (placement) {
        case Placement::SubpixelGrid: q = {grid(8), grid(8)}; break;
        case Placement::HalfSubpixelGrid: q = {grid(9), grid(9)}; break;
        case Placement::FineGrid: q = {grid(12), grid(12)}; break;
        case Placement::PixelCentres: q = {centre(), centre()}; break;
        case Placement::HalfPixelGrid: q = {grid(1), grid(1)}; break;
        case Placement::SampleRowEdge: q = {grid(9), grid(9)}; break;
        case Placement::TiesNearSamples: q = {nearSample(), nearSample()}; break;
      }
    }
    if (placement == Placement::SampleRowEdge) {
      if (rng() % 2) p[0].y = p[1].y = centre();
      else p[0].x = p[1].x = centre();
    }
    for (const glm::dvec2& q : p) v.push_back({float(ox + q.x), float(oy + q.y)});
  }
  return v;
}

std::vector<uint32_t> ourCounts(const std::vector<glm::vec2>& triangles, FillRule rule) {
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
  for (const glm::vec2 p : triangles) {
    indices.push_back(uint32_t(vertices.size()));
    vertices.push_back({glm::vec3(p, 0.5f)});
  }
  PipelineState state;
  state.viewport = {0, 0, kSize, kSize};
  state.positionSpace = PositionSpace::Window;
  state.format = FixedPointFormat::d16_8();
  state.fillRule = rule;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  Framebuffer fb(kSize, kSize, true);
  PipelineStatistics stats;
  const WindowSpaceVertexShader vs;
  const ConstantColorShader ps;
  const Status s = draw(
      fb, state,
      DrawCall<WindowSpaceVertexShader, ConstantColorShader>{vertices, indices, vs, ps}, stats);
  EXPECT_TRUE(s.isOk()) << s.message();
  return fb.countPlane();
}

struct Batch {
  Placement placement;
  int cell;
  std::vector<glm::vec2> triangles;
};

class LlvmpipeConformance : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    peer_ = peer::LlvmpipeCoverage::create(kSize, kSize, 2, error).release();
    error_ = error;
  }
  static void TearDownTestSuite() {
    delete peer_;
    peer_ = nullptr;
  }
  static peer::LlvmpipeCoverage* peer_;
  static std::string error_;
};
peer::LlvmpipeCoverage* LlvmpipeConformance::peer_ = nullptr;
std::string LlvmpipeConformance::error_;

// 25 batches of 4,096 triangles in 16-pixel cells and 4 of 256 in 64-pixel cells: 103,424
// triangles, every placement, each compared pixel for pixel.
TEST_F(LlvmpipeConformance, CoverageEqualsLlvmpipePixelForPixel) {
  ASSERT_NE(peer_, nullptr) << "llvmpipe: " << error_;
  const uint64_t seed = 0x11c0e000;
  std::cout << "[ seed ] " << seed << "; " << peer_->context().renderer() << "\n";
  std::mt19937_64 rng(seed);
  uint64_t triangles = 0, covered = 0, differing = 0;
  std::array<uint64_t, kPlacements> differingByPlacement{};
  for (int b = 0; b < 29; ++b) {
    const int cell = b < 25 ? 16 : 64;
    const int count = (kSize / cell) * (kSize / cell);
    const Placement placement = Placement(b % kPlacements);
    const std::vector<glm::vec2> tris = cellTriangles(rng, placement, cell, count);
    std::string error;
    const std::vector<uint32_t> theirs = peer_->countCoverage(tris, error);
    ASSERT_TRUE(error.empty()) << error;
    const std::vector<uint32_t> ours = ourCounts(tris, FillRule::BottomLeft);
    triangles += tris.size() / 3;
    int shown = 0;
    for (size_t i = 0; i < ours.size(); ++i) {
      covered += ours[i];
      ASSERT_LE(theirs[i], 1u) << "cells do not overlap";
      if (ours[i] == theirs[i]) continue;
      ++differing;
      ++differingByPlacement[size_t(placement)];
      const int x = int(i % kSize), y = int(i / kSize);
      const size_t t = size_t((y / cell) * (kSize / cell) + x / cell);
      if (shown++ < 3)
        ADD_FAILURE() << "batch " << b << ": pixel (" << x << ", " << y << ") ours " << ours[i]
                      << ", llvmpipe " << theirs[i] << "; triangle (" << tris[3 * t].x << ", "
                      << tris[3 * t].y << ") (" << tris[3 * t + 1].x << ", " << tris[3 * t + 1].y
                      << ") (" << tris[3 * t + 2].x << ", " << tris[3 * t + 2].y << ")";
    }
  }
  std::cout << triangles << " triangles, " << covered << " covered pixels, " << differing
            << " differ\n";
  EXPECT_EQ(differing, 0u);
  for (int p = 0; p < kPlacements; ++p) EXPECT_EQ(differingByPlacement[size_t(p)], 0u) << p;
  EXPECT_GE(triangles, 100000u);
  EXPECT_GT(covered, triangles * 5) << "not vacuous";
}

// The control: with our default rule (Direct3D's top-left, in our y-down image) the samples on
// horizontal edges go the other way, and the comparison sees it. Vertical and sloped edges and
// snapping agree, so those placements match even so.
TEST_F(LlvmpipeConformance, TopLeftRuleDiffersOnlyOnHorizontalEdges) {
  ASSERT_NE(peer_, nullptr) << "llvmpipe: " << error_;
  std::mt19937_64 rng(0x11c0e001);
  for (const Placement placement : {Placement::HalfPixelGrid, Placement::FineGrid}) {
    const std::vector<glm::vec2> tris = cellTriangles(rng, placement, 16, 4096);
    std::string error;
    const std::vector<uint32_t> theirs = peer_->countCoverage(tris, error);
    ASSERT_TRUE(error.empty()) << error;
    const std::vector<uint32_t> ours = ourCounts(tris, FillRule::TopLeft);
    uint64_t differing = 0, horizontal = 0;
    for (size_t i = 0; i < ours.size(); ++i) {
      if (ours[i] == theirs[i]) continue;
      ++differing;
      // The pixel's triangle has a horizontal edge through the pixel's sample row.
      const int x = int(i % kSize), y = int(i / kSize);
      const size_t t = size_t((y / 16) * (kSize / 16) + x / 16);
      for (int k = 0; k < 3; ++k) {
        const glm::vec2 a = tris[3 * t + k], b = tris[3 * t + (k + 1) % 3];
        horizontal += a.y == b.y && a.y == float(y) + 0.5f;
      }
    }
    if (placement == Placement::HalfPixelGrid) {
      EXPECT_GT(differing, 100u) << "ties on horizontal edges must show";
      EXPECT_EQ(horizontal, differing) << "every difference is on a horizontal edge";
    } else {
      EXPECT_EQ(differing, 0u) << "no sample lies on an edge at 1/4096 px";
    }
  }
}

}  // namespace
}  // namespace rast
