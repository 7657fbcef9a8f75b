// The draw's load op (PipelineState::clear) leaves exactly what Framebuffer::clear followed by the
// same draw leaves: every colour and depth sample, the counts and every statistic, whatever the
// state, the framebuffer's size (edge tiles), the samples per pixel and the thread count (1, 2, 4).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "pipeline/draw.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/lambert.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

// Not the clear values anywhere, and depths that would pass or fail differently from the clear
// depth: a tile the load op forgot to clear or to store differs from the reference.
void fillWithLeftovers(Framebuffer& fb) {
  for (size_t i = 0; i < fb.colorPlane().size(); ++i)
    fb.colorPlane()[i] = PackedColor(0x9e3779b9u * uint32_t(i + 1));
  for (size_t i = 0; i < fb.depthPlane().size(); ++i)
    fb.depthPlane()[i] = float((i * 7919) % 1000) / 1000.0f;
  for (size_t i = 0; i < fb.countPlane().size(); ++i) fb.countPlane()[i] = uint32_t(i % 5);
}

struct Outcome {
  std::vector<PackedColor> color;
  std::vector<float> depth;
  std::vector<uint32_t> counts;
  PipelineStatistics stats;
  bool drawn = false;
};

void expectSame(const Outcome& reference, const Outcome& loadOp) {
  EXPECT_EQ(reference.drawn, loadOp.drawn);
  EXPECT_TRUE(reference.color == loadOp.color);
  ASSERT_EQ(reference.depth.size(), loadOp.depth.size());
  // As bits: == would call -0 and 0 equal, and NaN unequal to itself.
  EXPECT_EQ(std::memcmp(reference.depth.data(), loadOp.depth.data(),
                        reference.depth.size() * sizeof(float)),
            0);
  EXPECT_TRUE(reference.counts == loadOp.counts);
  EXPECT_EQ(reference.stats, loadOp.stats);
}

struct Size {
  int width, height, samples;
  bool counts;
};

// One draw into a framebuffer of leftovers: cleared by Framebuffer::clear first (the reference),
// or by the draw's load op.
template <class Draw>
Outcome render(const Size& size, PipelineState state, const ClearValues& clear, bool loadOp,
               const ExecutionOptions& exec, const Draw& drawCall) {
  Framebuffer fb(size.width, size.height, size.counts, size.samples);
  fillWithLeftovers(fb);
  if (loadOp) state.clear = clear;
  else fb.clear(clear.color, clear.depth);
  Outcome out;
  out.drawn = bool(drawCall(fb, state, out.stats, exec));
  out.color = fb.colorPlane();
  out.depth = fb.depthPlane();
  out.counts = fb.countPlane();
  return out;
}

template <class Draw>
void expectLoadOpEqualsClear(const Size& size, const PipelineState& state, const ClearValues& clear,
                             const Draw& drawCall) {
  for (int threads : {1, 2, 4}) {
    ExecutionOptions exec;
    exec.threads = threads;
    SCOPED_TRACE(std::to_string(threads) + " threads");
    expectSame(render(size, state, clear, false, exec, drawCall),
               render(size, state, clear, true, exec, drawCall));
  }
}

class LoadOpClear : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(loadObj(std::string(RASTER_SHARED_MESHES) + "/bunny_lowres.obj", mesh_));
  }

  // The bunny framed, Lambert-shaded: partly covered tiles, untouched tiles and overdraw.
  auto bunny() const {
    return [this](Framebuffer& fb, const PipelineState& state, PipelineStatistics& stats,
                  const ExecutionOptions& exec) {
      const Camera camera = frameMesh(mesh_);
      const WorldNormalVertexShader vs{
          glm::mat4(1.0f), camera.viewProjection(float(fb.width()) / float(fb.height()))};
      const LambertShader ps{glm::vec3(0.85f, 0.8f, 0.7f), glm::vec3(0.08f), camera.eye * 2.0f,
                             glm::vec3(1.0f)};
      return draw(fb, state,
                  DrawCall<WorldNormalVertexShader, LambertShader>{mesh_.vertices, mesh_.indices,
                                                                   vs, ps},
                  stats, exec);
    };
  }

  static PipelineState viewportState(const Size& size) {
    PipelineState state;
    state.viewport = {0, 0, size.width, size.height};
    return state;
  }

  Mesh mesh_;
};

// 301 x 197: neither side a multiple of the 8-pixel tile, so edge tiles with padding lanes.
constexpr Size kOdd{301, 197, 1, true};
constexpr ClearValues kClear{glm::vec4(0.2f, 0.4f, 0.6f, 1.0f), 1.0f};

TEST_F(LoadOpClear, DepthTestedShadedMesh) {
  const PipelineState state = viewportState(kOdd);
  const Outcome drawn = render(kOdd, state, kClear, true, {}, bunny());
  // The draw is the point: fragments written, tiles untouched, and overdraw resolved by depth.
  EXPECT_GT(drawn.stats.fragmentsWritten, 5000u);
  EXPECT_GT(drawn.stats.depthTestsFailed, 0u);
  expectLoadOpEqualsClear(kOdd, state, kClear, bunny());
}

TEST_F(LoadOpClear, ColourWritesOffStillClearColour) {
  PipelineState state = viewportState(kOdd);
  state.colorWrite = false;  // W4: depth only, yet the load op clears colour as clear() does
  expectLoadOpEqualsClear(kOdd, state, kClear, bunny());
}

TEST_F(LoadOpClear, DepthUnusedStillClearsDepth) {
  PipelineState state = viewportState(kOdd);
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  expectLoadOpEqualsClear(kOdd, state, kClear, bunny());
}

TEST_F(LoadOpClear, ScissoredDrawClearsTheWholeFramebuffer) {
  PipelineState state = viewportState(kOdd);
  state.scissor = PixelRect{90, 40, 200, 150};
  const Outcome drawn = render(kOdd, state, kClear, true, {}, bunny());
  // Outside the scissor the framebuffer holds the clear values, not leftovers.
  EXPECT_EQ(drawn.color[0], packColor(kClear.color));
  EXPECT_EQ(drawn.depth[drawn.depth.size() - 1], kClear.depth);
  expectLoadOpEqualsClear(kOdd, state, kClear, bunny());
}

TEST_F(LoadOpClear, BlendedMultisampledQuantisedDepth) {
  for (int samples : {4, 8}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const Size size{123, 77, samples, false};
    PipelineState state = viewportState(size);
    state.blend = BlendState::alphaBlend();
    state.depth.format = DepthFormat::Unorm16;
    state.depth.compare = CompareOp::LessEqual;
    expectLoadOpEqualsClear(size, state, {glm::vec4(0.1f, 0.0f, 0.3f, 0.5f), 0.75f}, bunny());
  }
}

TEST_F(LoadOpClear, UnusualClearDepths) {
  const PipelineState state = viewportState(kOdd);
  // NaN fails every ordered compare; -0 must keep its sign; 0 makes every fragment fail Less.
  for (float depth : {std::numeric_limits<float>::quiet_NaN(), -0.0f, 0.0f, 0.5f}) {
    SCOPED_TRACE(depth);
    expectLoadOpEqualsClear(kOdd, state, {glm::vec4(1.0f, 0.0f, 0.0f, 1.0f), depth}, bunny());
  }
}

// Full-screen layers drawn front to back and back to front: whole tiles covered, the tile loop's
// deferred whole-tile writes and coarse bins.
TEST_F(LoadOpClear, FullScreenLayers) {
  const Size size{520, 260, 1, false};
  PipelineState state = viewportState(size);
  state.positionSpace = PositionSpace::Window;
  for (bool frontToBack : {true, false}) {
    std::vector<WindowVertex> vertices;
    std::vector<uint32_t> indices;
    for (int i = 0; i < 4; ++i) {
      const float z = 0.2f + 0.2f * float(frontToBack ? i : 3 - i);
      const uint32_t base = uint32_t(vertices.size());
      for (glm::vec2 p : {glm::vec2(0, 0), glm::vec2(size.width, 0),
                          glm::vec2(size.width, size.height), glm::vec2(0, size.height)})
        vertices.push_back({glm::vec3(p, z)});
      for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + k);
    }
    auto layers = [&](Framebuffer& fb, const PipelineState& s, PipelineStatistics& stats,
                      const ExecutionOptions& exec) {
      const WindowSpaceVertexShader vs;
      const ConstantColorShader ps{glm::vec4(0.9f, 0.5f, 0.1f, 1.0f)};
      return draw(fb, s,
                  DrawCall<WindowSpaceVertexShader, ConstantColorShader>{vertices, indices, vs, ps},
                  stats, exec);
    };
    SCOPED_TRACE(frontToBack ? "front to back" : "back to front");
    expectLoadOpEqualsClear(size, state, kClear, layers);
  }
}

// A draw that draws nothing still clears, as clear() would; a draw that fails validation clears
// nothing: the framebuffer keeps its leftovers.
TEST_F(LoadOpClear, EmptyDrawClearsAndInvalidDrawDoesNot) {
  const PipelineState state = viewportState(kOdd);
  const std::vector<WindowVertex> vertices = {{glm::vec3(1, 1, 0.5f)}};
  auto drawIndices = [&](std::vector<uint32_t> indices) {
    return [&vertices, indices](Framebuffer& fb, PipelineState s, PipelineStatistics& stats,
                                const ExecutionOptions& exec) {
      s.positionSpace = PositionSpace::Window;
      const WindowSpaceVertexShader vs;
      const ConstantColorShader ps{glm::vec4(1.0f)};
      return draw(fb, s,
                  DrawCall<WindowSpaceVertexShader, ConstantColorShader>{vertices, indices, vs, ps},
                  stats, exec);
    };
  };
  expectLoadOpEqualsClear(kOdd, state, kClear, drawIndices({}));
  const Outcome cleared = render(kOdd, state, kClear, true, {}, drawIndices({}));
  for (PackedColor c : cleared.color) ASSERT_EQ(c, packColor(kClear.color));
  for (float d : cleared.depth) ASSERT_EQ(d, kClear.depth);

  const Outcome invalid = render(kOdd, state, kClear, true, {}, drawIndices({0, 0, 7}));
  EXPECT_FALSE(invalid.drawn);
  Framebuffer leftovers(kOdd.width, kOdd.height, kOdd.counts, kOdd.samples);
  fillWithLeftovers(leftovers);
  EXPECT_TRUE(invalid.color == leftovers.colorPlane());
  EXPECT_EQ(std::memcmp(invalid.depth.data(), leftovers.depthPlane().data(),
                        invalid.depth.size() * sizeof(float)),
            0);
}

}  // namespace
}  // namespace rast
