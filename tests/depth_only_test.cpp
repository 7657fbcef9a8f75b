// A depth-only pass (colour writes off, a shader that cannot discard) runs no pixel shader, so the
// pipeline carries none of the shader's varyings past the vertex shader (draw.h, NoPixelShader).
// What it leaves must be what the same draw with colour on leaves, less the colour: the same
// depth bits, the same per-pixel counts and the same statistics but for the shader's invocations
// (a shader that may discard still runs, and its discards still decide what is written),
// on the bunny and on random clip-space triangles that cross the near and far planes (clipped,
// so their varyings would be interpolated at the new corners), with and without MSAA, in both
// depth formats that quantise and in float.
#include <gtest/gtest.h>

#include <random>

#include "bench/workloads.h"
#include "pipeline/draw.h"
#include "shaders_cpp/normal_visualizer.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/w1_lambert.h"
#include "tests/window_draw.h"

namespace rast {
namespace {

using testing_support::ClipVertex;
using testing_support::ClipVertexShader;

// Discards where the normal's x is negative: half the bunny's pixels.
struct DiscardingShader {
  static constexpr int kVaryings = 3;
  static constexpr bool kMayDiscard = true;
  PixelResult operator()(const Fragment<3>& f) const {
    if (f.varyings[0] < 0.0f) return PixelResult::discarded();
    return {glm::vec4(1.0f), false};
  }
};

template <class PS, class VS>
testing_support::DrawnFrame render(int width, int height, int samples, const PipelineState& state,
                                   const VS& vs, std::span<const typename VS::Vertex> vertices,
                                   std::span<const uint32_t> indices, int threads) {
  ExecutionOptions exec;
  exec.threads = threads;
  return testing_support::drawFrame<PS>(width, height, samples, true, state, vs, vertices,
                                        indices, exec);
}

// The draw with colour writes off against the same draw with them on: the depth-only one's colour
// must be the clear colour alone, and everything else the same.
template <class PS, class VS>
void expectDepthOnlyMatches(int width, int height, const VS& vs,
                            std::span<const typename VS::Vertex> vertices,
                            std::span<const uint32_t> indices, uint64_t minFragments) {
  for (int samples : {1, 4})
    for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24, DepthFormat::Unorm16})
      for (int threads : {1, 2}) {
        SCOPED_TRACE(testing::Message() << samples << " samples, depth format " << int(format)
                                        << ", " << threads << " threads");
        PipelineState state;
        state.viewport = {0, 0, width, height};
        state.depth.compare = CompareOp::Less;
        state.depth.write = true;
        state.depth.format = format;
        state.clear = ClearValues{glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f};
        const testing_support::DrawnFrame withColor =
            render<PS>(width, height, samples, state, vs, vertices, indices, threads);
        state.colorWrite = false;
        testing_support::DrawnFrame depthOnly =
            render<PS>(width, height, samples, state, vs, vertices, indices, threads);

        EXPECT_GT(withColor.stats.pixelShaderInvocations, 0u);
        // A shader that may discard still runs: its discards decide which depths are written.
        if constexpr (!PS::kMayDiscard) {
          EXPECT_EQ(depthOnly.stats.pixelShaderInvocations, 0u);
        }
        EXPECT_GE(depthOnly.stats.fragmentsWritten, minFragments);
        const PackedColor clear = packColor(state.clear->color);
        EXPECT_TRUE(std::all_of(depthOnly.color.begin(), depthOnly.color.end(),
                                [&](PackedColor c) { return c == clear; }));
        // The rest must agree: colour is compared as the depth-only frame has it.
        testing_support::DrawnFrame expected = withColor;
        expected.color = depthOnly.color;
        if constexpr (!PS::kMayDiscard) expected.stats.pixelShaderInvocations = 0;
        EXPECT_TRUE(testing_support::sameFrame(depthOnly, expected));
      }
}

TEST(DepthOnly, BunnyLeavesTheDepthAndCountsOfTheColourPass) {
  constexpr int kWidth = 480, kHeight = 270;
  workloads::LitMeshScene scene;
  ASSERT_TRUE(workloads::loadLitMeshScene(std::string(RASTER_SHARED_MESHES) + "/bunny.obj",
                                          kWidth, kHeight, scene));
  const WorldNormalVertexShader vs{glm::mat4(1.0f), scene.viewProjection};
  expectDepthOnlyMatches<W1LambertShader>(kWidth, kHeight, vs,
                                          std::span<const MeshVertex>(scene.mesh.vertices),
                                          scene.mesh.indices, 20000);
  // A shader that may discard keeps its varyings and runs in a depth-only pass too.
  expectDepthOnlyMatches<DiscardingShader>(kWidth, kHeight, vs,
                                           std::span<const MeshVertex>(scene.mesh.vertices),
                                           scene.mesh.indices, 5000);
}

// Triangles spread through and beyond the view volume in z and w: many cross the near plane
// (w small or negative at a corner) or the far one, and are clipped into fans.
TEST(DepthOnly, ClippedTrianglesLeaveTheDepthAndCountsOfTheColourPass) {
  constexpr int kWidth = 211, kHeight = 97;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
  for (int i = 0; i < 2000; ++i) {
    const float cx = 2.4f * unit(rng) - 1.2f, cy = 2.4f * unit(rng) - 1.2f;
    for (int v = 0; v < 3; ++v) {
      const float w = 3.0f * unit(rng) - 0.5f;
      const float x = cx + 0.6f * (unit(rng) - 0.5f), y = cy + 0.6f * (unit(rng) - 0.5f);
      const float z = 2.6f * unit(rng) - 1.3f;
      vertices.push_back({glm::vec4(x * w, y * w, z * w, w),
                          glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng))});
      indices.push_back(uint32_t(vertices.size() - 1));
    }
  }
  const ClipVertexShader vs;
  const std::span<const ClipVertex> span(vertices);
  expectDepthOnlyMatches<NormalVisualizerShader>(kWidth, kHeight, vs, span, indices, 2000);
  // The pass must have clipped triangles for this test to be about them.
  Framebuffer fb(kWidth, kHeight);
  PipelineState state;
  state.viewport = {0, 0, kWidth, kHeight};
  state.colorWrite = false;
  PipelineStatistics stats;
  ASSERT_TRUE(draw(fb, state,
                   DrawCall<ClipVertexShader, NormalVisualizerShader>{span, indices, vs,
                                                                    NormalVisualizerShader{}},
                   stats));
  EXPECT_GT(stats.clipClipped, 200u);
  EXPECT_GT(stats.clipNearOut + stats.clipFarOut, 200u);
}

}  // namespace
}  // namespace rast
