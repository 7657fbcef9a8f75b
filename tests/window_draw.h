// One draw of window-space triangles in a constant colour into a fresh, cleared framebuffer, and
// what it left: the tests that compare how a draw ran (threads, kernels, memory) start here.
#pragma once

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"

namespace rast::testing_support {

struct DrawnFrame {
  std::vector<PackedColor> color;
  std::vector<float> depth;
  std::vector<uint32_t> counts;  // empty unless counted
  PipelineStatistics stats;
};

// Colour, depth (as bits: float == would call -0 and 0 equal), counts and statistics equal.
inline testing::AssertionResult sameFrame(const DrawnFrame& a, const DrawnFrame& b) {
  if (a.color != b.color) return testing::AssertionFailure() << "colour differs";
  if (a.depth.size() != b.depth.size() ||
      std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) != 0)
    return testing::AssertionFailure() << "depth differs";
  if (a.counts != b.counts) return testing::AssertionFailure() << "counts differ";
  if (!(a.stats == b.stats)) return testing::AssertionFailure() << "statistics differ";
  return testing::AssertionSuccess();
}

inline DrawnFrame drawWindowTriangles(int width, int height, const std::vector<WindowVertex>& vertices,
                                      const std::vector<uint32_t>& indices, glm::vec4 color,
                                      const ExecutionOptions& exec, bool counts = false) {
  Framebuffer fb(width, height, counts);
  fb.clear(glm::vec4(0, 0, 0, 1), 1.0f);
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.positionSpace = PositionSpace::Window;
  const WindowSpaceVertexShader vs;
  const ConstantColorShader ps{color};
  DrawnFrame f;
  EXPECT_TRUE(draw(fb, state,
                   DrawCall<WindowSpaceVertexShader, ConstantColorShader>{vertices, indices, vs, ps},
                   f.stats, exec));
  f.color = fb.colorPlane();
  f.depth = fb.depthPlane();
  f.counts = fb.countPlane();
  return f;
}

}  // namespace rast::testing_support
