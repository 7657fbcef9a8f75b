// One draw into a fresh framebuffer, and what it left: the tests that compare how a draw ran
// (threads, kernels, memory, shortcuts) start here. Window-space triangles in a constant colour,
// or any vertex and pixel shader, with a clip-space vertex carrying a normal for the latter.
#pragma once

#include <cstring>
#include <span>
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

// A clip-space vertex with a normal, which its shader passes on as three varyings: random
// clip-space triangles for shaders that read a normal.
struct ClipVertex {
  glm::vec4 position;
  glm::vec3 normal;
};
struct ClipVertexShader {
  using Vertex = ClipVertex;
  static constexpr int kVaryings = 3;
  ShadedVertex<3> operator()(const Vertex& v) const {
    return {v.position, {v.normal.x, v.normal.y, v.normal.z}};
  }
};

// One draw with pixel shader PS (default-constructed) into a fresh framebuffer of `samples`
// samples (with a count plane when `counts`), and what it left.
template <class PS, class VS>
DrawnFrame drawFrame(int width, int height, int samples, bool counts, const PipelineState& state,
                     const VS& vs, std::span<const typename VS::Vertex> vertices,
                     std::span<const uint32_t> indices, const ExecutionOptions& exec) {
  Framebuffer fb(width, height, counts, samples);
  DrawnFrame f;
  EXPECT_TRUE(draw(fb, state, DrawCall<VS, PS>{vertices, indices, vs, PS{}}, f.stats, exec));
  f.color = fb.colorPlane();
  f.depth = fb.depthPlane();
  f.counts = fb.countPlane();
  return f;
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
