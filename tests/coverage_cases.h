// Coverage test cases shared by the exact-reference and float-mode tests: random window-space
// triangles, and a pixel shader that records which triangles wrote each pixel.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <random>
#include <vector>

#include "pipeline/draw.h"
#include "shaders_cpp/window_space.h"
#include "rasterizer/fixed_point.h"
#include "reference/exact_rasterizer.h"

namespace rast::test_support {

using reference::WindowPoint;
using reference::WindowTriangle;

// Random window-space triangles that stress the rules: vertices on the subpixel grid, exactly on
// rounding ties, on pixel centres; axis-aligned edges through samples; sub-pixel triangles,
// slivers, and triangles far larger than the framebuffer (past the 32-bit kernel range at 16.8).
inline WindowTriangle randomTriangle(std::mt19937_64& rng, FixedPointFormat format, int width,
                              int height) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double unit = format.subpixelsPerPixel();
  auto inView = [&] { return WindowPoint{-16 + u(rng) * (width + 32), -16 + u(rng) * (height + 32)}; };
  WindowTriangle t;
  switch (rng() % 8) {
    case 0:
      for (auto& p : t) p = inView();
      break;
    case 1:  // on the subpixel grid
      for (auto& p : t) {
        p = inView();
        p = {std::round(p.x * unit) / unit, std::round(p.y * unit) / unit};
      }
      break;
    case 2:  // halfway between subpixels: ties
      for (auto& p : t) {
        p = inView();
        p = {(std::floor(p.x * unit) + 0.5) / unit, (std::floor(p.y * unit) + 0.5) / unit};
      }
      break;
    case 3:  // on pixel centres
      for (auto& p : t) {
        p = inView();
        p = {std::floor(p.x) + 0.5, std::floor(p.y) + 0.5};
      }
      break;
    case 4: {  // a right angle at a pixel centre, legs along the axes
      const WindowPoint c = inView();
      const double x = std::floor(c.x) + 0.5, y = std::floor(c.y) + 0.5;
      const double l = double(int(rng() % 41) - 20), m = double(int(rng() % 41) - 20);
      t = {{{x, y}, {x + l, y}, {x, y + m}}};
      break;
    }
    case 5: {  // smaller than a pixel
      const WindowPoint c = inView();
      for (auto& p : t) p = {c.x + 3 * (u(rng) - 0.5), c.y + 3 * (u(rng) - 0.5)};
      break;
    }
    case 6: {  // a sliver: the third vertex within a subpixel of the segment between the others
      t[0] = inView();
      t[1] = inView();
      const double s = u(rng), off = (u(rng) - 0.5) * 2 / unit;
      t[2] = {t[0].x + s * (t[1].x - t[0].x) + off, t[0].y + s * (t[1].y - t[0].y) - off};
      break;
    }
    default: {  // huge, inside the guard band
      const double reach = std::min(format.guardBandPixels() - 1, 60000.0);
      for (auto& p : t) p = {(2 * u(rng) - 1) * reach, (2 * u(rng) - 1) * reach};
      t[0] = inView();
      break;
    }
  }
  // The pipeline takes float positions: the reference gets exactly the same values.
  return reference::roundedToFloat(t);
}

// Per pixel, a sum of hashes of the triangles that wrote it: with the count, a pixel covered by
// the wrong triangles cannot agree with the reference by accident.
struct TriangleHashShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kSideEffects = true;  // records every passing fragment
  uint64_t* hashes;
  int width;
  PixelResult operator()(const Fragment<0>& f) const {
    hashes[size_t(f.y) * size_t(width) + size_t(f.x)] += hashTriangle(f.primitiveId);
    return {};
  }
  static uint64_t hashTriangle(uint64_t id) {  // splitmix64
    uint64_t z = id + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
};

struct DrawnCoverage {
  std::vector<uint32_t> counts;  // the count framebuffer
  std::vector<uint64_t> hashes;  // per pixel, the sum of TriangleHashShader's triangle hashes
  PipelineStatistics stats;
  Status status = Status::ok();
};

// One draw of the triangles (triangle i is primitive i) with the real pipeline: window-space
// pass-through, depth compare Always with no writes, so every covered sample is counted.
inline DrawnCoverage drawWindowTriangles(const std::vector<WindowTriangle>& triangles, int width,
                                         int height, FixedPointFormat format, RasterMode mode) {
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
  for (const WindowTriangle& t : triangles)
    for (const WindowPoint& p : t) {
      indices.push_back(uint32_t(vertices.size()));
      vertices.push_back({glm::vec3(float(p.x), float(p.y), 0.5f)});
    }
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.positionSpace = PositionSpace::Window;
  state.format = format;
  state.rasterMode = mode;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  Framebuffer fb(width, height, true);
  DrawnCoverage out;
  out.hashes.assign(size_t(width) * size_t(height), 0);
  const WindowSpaceVertexShader vs;
  const TriangleHashShader ps{out.hashes.data(), width};
  out.status = draw(fb, state,
                    DrawCall<WindowSpaceVertexShader, TriangleHashShader>{vertices, indices, vs, ps},
                    out.stats);
  out.counts = std::move(fb.countPlane());
  return out;
}

}  // namespace rast::test_support
