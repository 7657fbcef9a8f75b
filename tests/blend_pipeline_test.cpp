// Blending and the colour write mask through the whole pipeline: the merge blends each written
// sample with that sample's stored colour, and only where every test passed.
#include <gtest/gtest.h>

#include <vector>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

PipelineState windowState(int w, int h) {
  PipelineState state;
  state.viewport = {0, 0, w, h};
  state.positionSpace = PositionSpace::Window;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  return state;
}

// A triangle covering the left half of a w x h framebuffer exactly on pixel boundaries is hard
// to make; a big one covering everything is easy and enough here.
const std::vector<WindowVertex> kEverything = {{{-100, -100, 0.5f}}, {{300, -100, 0.5f}},
                                               {{-100, 300, 0.5f}}};

Status drawColor(Framebuffer& fb, const PipelineState& state, const std::vector<WindowVertex>& v,
                 glm::vec4 color, PipelineStatistics& stats) {
  std::vector<uint32_t> idx(v.size());
  for (size_t i = 0; i < v.size(); ++i) idx[i] = uint32_t(i);
  const WindowSpaceVertexShader vs;
  const ConstantColorShader ps{color};
  return draw(fb, state, DrawCall<WindowSpaceVertexShader, ConstantColorShader>{v, idx, vs, ps},
              stats);
}

TEST(BlendPipeline, AlphaBlendOverTheClearColour) {
  Framebuffer fb(16, 8);
  fb.clear(glm::vec4(0, 1, 0.2f, 1), 1.0f);
  PipelineState state = windowState(16, 8);
  state.blend = BlendState::alphaBlend();
  PipelineStatistics stats;
  const glm::vec4 src(1, 0, 0, 0.5f);
  ASSERT_TRUE(drawColor(fb, state, kEverything, src, stats));
  const PackedColor expected = blendAndPack(src, packColor(glm::vec4(0, 1, 0.2f, 1)), state.blend);
  // By hand: red 1 * 0.5 + 0 = 0.5 -> 128, green 0 + 1 * 0.5 -> 128, alpha 0.5 + 1 * 0.5 = 1.
  EXPECT_EQ(expected & 0xff, 128u);
  EXPECT_EQ((expected >> 8) & 0xff, 128u);
  EXPECT_EQ(expected >> 24, 255u);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) ASSERT_EQ(fb.color(x, y), expected) << x << "," << y;
  EXPECT_EQ(stats.samplesBlended, 16u * 8u);
}

TEST(BlendPipeline, AdditiveLayersAccumulateAndSaturate) {
  Framebuffer fb(8, 8);
  fb.clear(glm::vec4(0, 0, 0, 0), 1.0f);
  PipelineState state = windowState(8, 8);
  state.blend = {true, BlendOp::Add, BlendFactor::One, BlendFactor::One,
                 BlendOp::Add, BlendFactor::One, BlendFactor::One, glm::vec4(0)};
  PipelineStatistics stats;
  // 0.25 is 63.75 of 255: stored as 64, read back as 64/255; each layer adds 0.25 again.
  PackedColor expected = packColor(glm::vec4(0));
  for (int layer = 0; layer < 6; ++layer) {
    ASSERT_TRUE(drawColor(fb, state, kEverything, glm::vec4(0.25f, 0.5f, 0, 1), stats));
    expected = blendAndPack(glm::vec4(0.25f, 0.5f, 0, 1), expected, state.blend);
    ASSERT_EQ(fb.color(3, 4), expected) << "layer " << layer;
  }
  EXPECT_EQ(expected & 0xff, 255u);  // saturated
  EXPECT_EQ((expected >> 8) & 0xff, 255u);
}

TEST(BlendPipeline, WriteMaskKeepsOtherChannels) {
  Framebuffer fb(8, 8);
  fb.clear(glm::vec4(0.2f, 0.4f, 0.6f, 0.8f), 1.0f);
  const PackedColor before = fb.color(0, 0);
  PipelineState state = windowState(8, 8);
  state.colorWriteMask = kWriteGreen | kWriteAlpha;
  PipelineStatistics stats;
  ASSERT_TRUE(drawColor(fb, state, kEverything, glm::vec4(1, 1, 1, 1), stats));
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      ASSERT_EQ(fb.color(x, y), (before & 0x00ff00ffu) | 0xff00ff00u);
  EXPECT_EQ(stats.samplesBlended, 0u);  // masking is not blending
}

// Depth decides before blending: a farther layer neither blends nor writes.
TEST(BlendPipeline, FailedDepthDoesNotBlend) {
  Framebuffer fb(8, 8);
  fb.clear(glm::vec4(0, 0, 0, 1), 0.25f);
  PipelineState state = windowState(8, 8);
  state.depth.compare = CompareOp::Less;
  state.blend = BlendState::alphaBlend();
  PipelineStatistics stats;
  ASSERT_TRUE(drawColor(fb, state, kEverything, glm::vec4(1, 1, 1, 0.5f), stats));  // z 0.5
  EXPECT_EQ(stats.samplesBlended, 0u);
  EXPECT_EQ(fb.color(2, 2), packColor(glm::vec4(0, 0, 0, 1)));
}

// With MSAA each sample blends with its own stored colour: on an edge pixel the covered
// samples change and the others keep the clear colour.
TEST(BlendPipeline, MultisampleBlendsPerSample) {
  Framebuffer fb(8, 8, false, 4);
  fb.clear(glm::vec4(0, 0, 1, 1), 1.0f);
  PipelineState state = windowState(8, 8);
  state.blend = BlendState::alphaBlend();
  PipelineStatistics stats;
  // A vertical edge at x = 4.0: samples with offset x < 0 in column 3 are left of 3.5 ... every
  // sample of columns 0..3 is inside, none of 4..7 (offsets are within +-7/16 of the centre).
  const std::vector<WindowVertex> left = {{{-50, -50, 0.5f}}, {{4, -50, 0.5f}}, {{4, 50, 0.5f}},
                                          {{-50, -50, 0.5f}}, {{4, 50, 0.5f}}, {{-50, 50, 0.5f}}};
  ASSERT_TRUE(drawColor(fb, state, left, glm::vec4(1, 0, 0, 0.5f), stats));
  const PackedColor blended =
      blendAndPack(glm::vec4(1, 0, 0, 0.5f), packColor(glm::vec4(0, 0, 1, 1)), state.blend);
  for (int s = 0; s < 4; ++s) {
    EXPECT_EQ(fb.sampleColor(3, 5, s), blended);
    EXPECT_EQ(fb.sampleColor(4, 5, s), packColor(glm::vec4(0, 0, 1, 1)));
  }
  EXPECT_EQ(stats.samplesBlended, 4u * 8u * 4u);
}

}  // namespace
}  // namespace rast
