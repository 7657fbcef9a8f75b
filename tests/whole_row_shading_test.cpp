// Shaders declared kWholeRows run on every lane of the rows a triangle covers, in vector
// instructions, and have their colours packed a row at a time: the colour, depth and statistics
// equal those of the same shader run pixel by pixel, for both builds of the tile loop, with and
// without MSAA, on the bunny and on random clip-space triangles whose varyings, extrapolated to
// the lanes they do not cover, overflow to infinities and NaNs.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "bench/workloads.h"
#include "pipeline/draw.h"
#include "shaders_cpp/lambert.h"
#include "shaders_cpp/normal_visualizer.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/w1_lambert.h"
#include "tests/window_draw.h"

namespace rast {
namespace {

static_assert(kShadesWholeRows<W1LambertShader> && kShadesWholeRows<NormalVisualizerShader> &&
              kShadesWholeRows<LambertShader>);

// The same shader without the declaration: run on the covered pixels one by one.
template <class PS>
struct PerPixel {
  static constexpr int kVaryings = PS::kVaryings;
  static constexpr bool kMayDiscard = false;
  PS inner;
  PixelResult operator()(const Fragment<kVaryings>& f) const { return inner(f); }
};
static_assert(!kShadesWholeRows<PerPixel<W1LambertShader>>);

using testing_support::ClipVertex;
using testing_support::ClipVertexShader;
using Result = testing_support::DrawnFrame;  // counts unused
using testing_support::sameFrame;

PipelineState clipState(int width, int height) {
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.depth.compare = CompareOp::Less;
  state.depth.write = true;
  state.clear = ClearValues{glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f};
  return state;
}

template <class PS, class VS>
Result render(int width, int height, int samples, const PipelineState& state, const VS& vs,
              std::span<const typename VS::Vertex> vertices, std::span<const uint32_t> indices,
              BackEndTarget target) {
  ExecutionOptions exec;
  exec.backEnd = target;
  return testing_support::drawFrame<PS>(width, height, samples, false, state, vs, vertices,
                                        indices, exec);
}

TEST(WholeRowShading, BunnyEqualsPerPixelShading) {
  constexpr int kWidth = 480, kHeight = 270;
  workloads::LitMeshScene scene;
  ASSERT_TRUE(workloads::loadLitMeshScene(std::string(RASTER_SHARED_MESHES) + "/bunny.obj",
                                          kWidth, kHeight, scene));
  const WorldNormalVertexShader vs{glm::mat4(1.0f), scene.viewProjection};
  for (int samples : {1, 4})
    for (BackEndTarget target : {BackEndTarget::Auto, BackEndTarget::Baseline}) {
      SCOPED_TRACE(testing::Message() << samples << " samples, back end " << int(target));
      const PipelineState state = clipState(kWidth, kHeight);
      const std::span<const MeshVertex> vertices = scene.mesh.vertices;
      const Result rows = render<W1LambertShader>(kWidth, kHeight, samples, state, vs, vertices,
                                                  scene.mesh.indices, target);
      EXPECT_TRUE(sameFrame(rows, render<PerPixel<W1LambertShader>>(
                                       kWidth, kHeight, samples, state, vs, vertices,
                                       scene.mesh.indices, target)));
      EXPECT_TRUE(sameFrame(render<NormalVisualizerShader>(kWidth, kHeight, samples, state, vs,
                                                            vertices, scene.mesh.indices, target),
                             render<PerPixel<NormalVisualizerShader>>(
                                 kWidth, kHeight, samples, state, vs, vertices,
                                 scene.mesh.indices, target)));
      EXPECT_TRUE(sameFrame(render<LambertShader>(kWidth, kHeight, samples, state, vs, vertices,
                                                   scene.mesh.indices, target),
                             render<PerPixel<LambertShader>>(kWidth, kHeight, samples, state, vs,
                                                             vertices, scene.mesh.indices,
                                                             target)));
      EXPECT_GT(rows.stats.pixelShaderInvocations, 20000u);
    }
}

// Thin triangles with w from 1/100 to 100 and normals from 1e-30 to 1e30: extrapolated past a
// triangle's edges, 1/w crosses zero and the normals overflow, so uncovered lanes of a row shade
// infinities and NaNs, which must not reach any written pixel; covered lanes with a normal of
// 1e-30 normalise 0/0 (NaN, packed as 0) and with 1e30 overflow, the same on both paths.
TEST(WholeRowShading, NonFiniteLanesStayOutOfTheImage) {
  constexpr int kWidth = 203, kHeight = 117;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
  for (int i = 0; i < 3000; ++i) {
    const float cx = 2.0f * unit(rng) - 1.0f, cy = 2.0f * unit(rng) - 1.0f;
    for (int v = 0; v < 3; ++v) {
      const float w = std::pow(10.0f, 4.0f * unit(rng) - 2.0f);
      const float scale = std::pow(10.0f, 60.0f * unit(rng) - 30.0f);
      const float x = cx + 0.1f * (unit(rng) - 0.5f), y = cy + 0.1f * (unit(rng) - 0.5f);
      vertices.push_back({glm::vec4(x * w, y * w, unit(rng) * w, w),
                          scale * glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng))});
      indices.push_back(uint32_t(vertices.size() - 1));
    }
  }
  const ClipVertexShader vs;
  for (int samples : {1, 4})
    for (BackEndTarget target : {BackEndTarget::Auto, BackEndTarget::Baseline}) {
      SCOPED_TRACE(testing::Message() << samples << " samples, back end " << int(target));
      const PipelineState state = clipState(kWidth, kHeight);
      const Result rows =
          render<W1LambertShader>(kWidth, kHeight, samples, state, vs,
                                  std::span<const ClipVertex>(vertices), indices, target);
      EXPECT_TRUE(sameFrame(rows, render<PerPixel<W1LambertShader>>(
                                       kWidth, kHeight, samples, state, vs,
                                       std::span<const ClipVertex>(vertices), indices, target)));
      EXPECT_GT(rows.stats.fragmentsWritten, 5000u);
    }
}

}  // namespace
}  // namespace rast
