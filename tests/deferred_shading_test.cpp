// Hidden-surface removal before shading (tile_loop.h, ExecutionOptions::deferShading): a tile
// shades only the fragments it keeps, and the colour, depth, counts and statistics equal those of
// shading every passing fragment as it passes; the shader runs exactly once per kept pixel.
#include <gtest/gtest.h>

#include <atomic>
#include <random>

#include "bench/workloads.h"
#include "pipeline/draw.h"
#include "shaders_cpp/lambert.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/w1_lambert.h"
#include "tests/window_draw.h"

namespace rast {
namespace {

using testing_support::ClipVertex;
using testing_support::ClipVertexShader;
using testing_support::DrawnFrame;
using testing_support::sameFrame;

// W1's shading, run pixel by pixel (not kWholeRows), counting its runs.
struct CountingShader {
  static constexpr int kVaryings = 3;
  static constexpr bool kMayDiscard = false;
  std::atomic<uint64_t>* runs;
  PixelResult operator()(const Fragment<3>& f) const {
    runs->fetch_add(1, std::memory_order_relaxed);
    return W1LambertShader{}(f);
  }
};

PipelineState depthState(int width, int height) {
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.depth.compare = CompareOp::Less;
  state.depth.write = true;
  state.clear = ClearValues{glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f};
  return state;
}

template <class PS, class VS>
DrawnFrame render(int width, int height, const PipelineState& state, const VS& vs,
                  std::span<const typename VS::Vertex> vertices,
                  std::span<const uint32_t> indices, int threads, bool defer,
                  BackEndTarget target = BackEndTarget::Auto) {
  ExecutionOptions exec;
  exec.threads = threads;
  exec.deferShading = defer;
  exec.backEnd = target;
  return testing_support::drawFrame<PS>(width, height, 1, true, state, vs, vertices, indices, exec);
}

// 4000 random clip-space triangles of about `size` (every 50th of 1.5, covering whole tiles)
// stacked over the view at w from 0.5 to 1.5, their three varyings in [0, 1) + varyingOffset.
struct StackedTriangles {
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
};
StackedTriangles stackedTriangles(uint32_t seed, float size, glm::vec3 varyingOffset) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  StackedTriangles out;
  for (int i = 0; i < 4000; ++i) {
    const float cx = 2.2f * unit(rng) - 1.1f, cy = 2.2f * unit(rng) - 1.1f;
    const float s = i % 50 == 0 ? 1.5f : size;
    for (int v = 0; v < 3; ++v) {
      const float w = 0.5f + unit(rng);
      out.vertices.push_back({glm::vec4((cx + s * (unit(rng) - 0.5f)) * w,
                                        (cy + s * (unit(rng) - 0.5f)) * w, unit(rng) * w, w),
                              glm::vec3(unit(rng), unit(rng), unit(rng)) + varyingOffset});
      out.indices.push_back(uint32_t(out.vertices.size() - 1));
    }
  }
  return out;
}

// The bunny, closed, drawn without culling: its back faces pass first where they are drawn first,
// then lose to the front faces, so a third of the passing fragments are overwritten in their tile.
TEST(DeferredShading, BunnyEqualsShadingEveryPassingFragment) {
  constexpr int kWidth = 480, kHeight = 270;
  workloads::LitMeshScene scene;
  ASSERT_TRUE(workloads::loadLitMeshScene(std::string(RASTER_SHARED_MESHES) + "/bunny.obj",
                                          kWidth, kHeight, scene));
  const WorldNormalVertexShader vs{glm::mat4(1.0f), scene.viewProjection};
  const std::span<const MeshVertex> vertices = scene.mesh.vertices;
  const std::span<const uint32_t> indices = scene.mesh.indices;
  for (const CompareOp op : {CompareOp::Less, CompareOp::LessEqual, CompareOp::Always})
    for (const int threads : {1, 2})
      for (const BackEndTarget target : {BackEndTarget::Auto, BackEndTarget::Baseline}) {
        SCOPED_TRACE(testing::Message() << "op " << int(op) << ", " << threads
                                        << " threads, back end " << int(target));
        PipelineState state = depthState(kWidth, kHeight);
        state.depth.compare = op;
        const DrawnFrame deferred =
            render<W1LambertShader>(kWidth, kHeight, state, vs, vertices, indices, threads, true, target);
        EXPECT_TRUE(sameFrame(deferred, render<W1LambertShader>(kWidth, kHeight, state, vs, vertices,
                                                                indices, threads, false, target)));
        EXPECT_TRUE(sameFrame(
            render<LambertShader>(kWidth, kHeight, state, vs, vertices, indices, threads, true, target),
            render<LambertShader>(kWidth, kHeight, state, vs, vertices, indices, threads, false, target)));
        EXPECT_GT(deferred.stats.pixelShaderInvocations, 20000u);
      }
}

// The shader runs once per pixel the frame keeps, where shading as fragments pass runs it once per
// passing fragment; both count every passing fragment. Random clip-space triangles stacked over a
// frame whose size leaves partial tiles at the right and bottom edges.
TEST(DeferredShading, ShaderRunsOncePerKeptPixel) {
  constexpr int kWidth = 203, kHeight = 117;
  const auto [vertices, indices] = stackedTriangles(11, 0.15f, glm::vec3(-0.5f, -0.5f, 0.0f));
  const ClipVertexShader vs;
  const PipelineState state = depthState(kWidth, kHeight);
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    DrawnFrame frames[2];
    uint64_t runs[2];
    for (const bool defer : {false, true}) {
      std::atomic<uint64_t> counted = 0;
      ExecutionOptions exec;
      exec.threads = threads;
      exec.deferShading = defer;
      Framebuffer fb(kWidth, kHeight, true);
      DrawnFrame& f = frames[defer];
      ASSERT_TRUE(draw(fb, state,
                       DrawCall<ClipVertexShader, CountingShader>{
                           std::span<const ClipVertex>(vertices), indices, vs,
                           CountingShader{&counted}},
                       f.stats, exec));
      f.color = fb.colorPlane();
      f.depth = fb.depthPlane();
      f.counts = fb.countPlane();
      runs[defer] = counted;
    }
    EXPECT_TRUE(sameFrame(frames[0], frames[1]));
    EXPECT_EQ(runs[false], frames[0].stats.pixelShaderInvocations);
    // Kept pixels: those some fragment passed at (depth below the clear value of 1).
    uint64_t kept = 0;
    for (const float z : frames[1].depth) kept += z < 1.0f;
    EXPECT_EQ(runs[true], kept);
    EXPECT_LT(2 * kept, frames[1].stats.pixelShaderInvocations);  // overdraw of more than 2
  }
}

// A kWholeRows shader whose colour depends on every input a fragment has: a tile shades its kept
// pixels in one pass over their rows, each lane with the varyings, depth, facing and id of the
// triangle that owns it, and the result equals shading as fragments pass and shading pixel by
// pixel. Random triangles of both facings (no culling) and ids up to 4000, stacked deep.
struct EveryInputShader {
  static constexpr int kVaryings = 3;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kWholeRows = true;  // arithmetic only: safe on any lane
  PixelResult operator()(const Fragment<3>& f) const {
    const float id = float(f.primitiveId % 61) / 61.0f;
    const float where = float((f.x * 3 + f.y * 5) & 15) / 32.0f;
    return {glm::vec4(glm::fract(f.varyings[0] * 3.0f + f.depth * 17.0f),
                      glm::fract(f.varyings[1] * 2.0f + id), (f.frontFacing ? 0.5f : 0.0f) + where,
                      glm::fract(f.varyings[2] + f.depth * 5.0f))};
  }
};
struct EveryInputPerPixel {  // the same shader without kWholeRows: run on kept pixels one by one
  static constexpr int kVaryings = 3;
  static constexpr bool kMayDiscard = false;
  PixelResult operator()(const Fragment<3>& f) const { return EveryInputShader{}(f); }
};
static_assert(kShadesWholeRows<EveryInputShader> && !kShadesWholeRows<EveryInputPerPixel>);

TEST(DeferredShading, OnePassPerTileGivesEachLaneItsOwnersInputs) {
  constexpr int kWidth = 203, kHeight = 117;
  const auto [vertices, indices] = stackedTriangles(23, 0.12f, glm::vec3(0.0f));
  const ClipVertexShader vs;
  const std::span<const ClipVertex> span(vertices);
  const PipelineState state = depthState(kWidth, kHeight);
  for (const int threads : {1, 2})
    for (const BackEndTarget target : {BackEndTarget::Auto, BackEndTarget::Baseline}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, back end " << int(target));
      const DrawnFrame rows = render<EveryInputShader>(kWidth, kHeight, state, vs, span, indices,
                                                       threads, true, target);
      EXPECT_TRUE(sameFrame(rows, render<EveryInputShader>(kWidth, kHeight, state, vs, span,
                                                           indices, threads, false, target)));
      EXPECT_TRUE(sameFrame(rows, render<EveryInputPerPixel>(kWidth, kHeight, state, vs, span,
                                                             indices, threads, true, target)));
      EXPECT_GT(rows.stats.pixelShaderInvocations, 3u * kWidth * kHeight / 2);  // passing, not kept
    }
}

// Blending keeps every passing fragment's colour in the result: nothing is deferred, and the
// shader runs once per passing fragment whatever the option says.
TEST(DeferredShading, BlendingShadesEveryPassingFragment) {
  constexpr int kWidth = 64, kHeight = 48;
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
  for (int layer = 0; layer < 4; ++layer) {
    const float z = 0.8f - 0.1f * float(layer);  // each nearer than the last: every one passes
    for (const glm::vec2 p : {glm::vec2(-1, -1), glm::vec2(3, -1), glm::vec2(-1, 3)}) {
      vertices.push_back({glm::vec4(p, z, 1.0f), glm::vec3(0.2f, 0.3f, 0.9f)});
      indices.push_back(uint32_t(vertices.size() - 1));
    }
  }
  PipelineState state = depthState(kWidth, kHeight);
  state.blend = BlendState::alphaBlend();
  std::atomic<uint64_t> counted = 0;
  Framebuffer fb(kWidth, kHeight);
  PipelineStatistics stats;
  const ClipVertexShader vs;
  ASSERT_TRUE(draw(fb, state,
                   DrawCall<ClipVertexShader, CountingShader>{std::span<const ClipVertex>(vertices),
                                                              indices, vs, CountingShader{&counted}},
                   stats));
  EXPECT_EQ(counted, 4u * kWidth * kHeight);
  EXPECT_EQ(stats.pixelShaderInvocations, 4u * kWidth * kHeight);
}

}  // namespace
}  // namespace rast
