// The benchmark workloads (bench/workloads.h) are what ../shared/design/workloads.md defines.
#include <gtest/gtest.h>

#include <algorithm>

#include "bench/workloads.h"

namespace rast::workloads {
namespace {

// Small enough to be quick, 16:9 like the benchmark frame.
constexpr int kWidth = 256, kHeight = 144;

TEST(Workloads, TinyTriangleGridsHaveTheDefinedTriangleCounts) {
  const int expected[] = {2'075'024, 208'120, 20'944, 2'150};
  for (size_t k = 0; k < kTinyTriangleAreas.size(); ++k) {
    const int area = kTinyTriangleAreas[k];
    SCOPED_TRACE("area " + std::to_string(area));
    EXPECT_EQ(triangleGridSize(area, kFrameWidth, kFrameHeight).triangleCount(), expected[k]);
    EXPECT_EQ(triangleGrid(area, kFrameWidth, kFrameHeight, kTinyTriangleDepth).triangleCount(),
              size_t(expected[k]));
  }
}

TEST(Workloads, TinyTriangleGridsCoverEveryPixelOnce) {
  PipelineState state = workloadState(kWidth, kHeight, PositionSpace::Window);
  state.depth.compare = CompareOp::Always;
  for (int area : kTinyTriangleAreas) {
    SCOPED_TRACE("area " + std::to_string(area));
    Framebuffer fb(kWidth, kHeight, true);
    fb.clear(kClearColor, kClearDepth);
    PipelineStatistics stats;
    ASSERT_TRUE(drawFlatGeometry(fb, state, triangleGrid(area, kWidth, kHeight, kTinyTriangleDepth),
                                 stats));
    const auto& counts = fb.countPlane();
    EXPECT_TRUE(std::all_of(counts.begin(), counts.end(), [](uint32_t c) { return c == 1; }));
    EXPECT_EQ(stats.samplesCovered, uint64_t(kWidth) * kHeight);
  }
}

TEST(Workloads, TessellatedLayersHaveTheDefinedTriangleCount) {
  EXPECT_EQ(overdrawLayers(kFrameWidth, kFrameHeight, LayerOrder::FrontToBack,
                           LayerShape::Tessellated)
                .triangleCount(),
            34'400u);
  EXPECT_EQ(overdrawLayers(kFrameWidth, kFrameHeight, LayerOrder::FrontToBack, LayerShape::Quad)
                .triangleCount(),
            32u);
}

TEST(Workloads, OverdrawLayersRasterizeSixteenTimesAndPassDepthAsOrdered) {
  const uint64_t pixels = uint64_t(kWidth) * kHeight;
  for (LayerShape shape : {LayerShape::Quad, LayerShape::Tessellated}) {
    SCOPED_TRACE(shape == LayerShape::Quad ? "quads" : "tessellated");
    Framebuffer fb(kWidth, kHeight);
    PipelineStatistics frontToBack, backToFront;
    ASSERT_TRUE(renderW3Frame(
        fb, overdrawLayers(kWidth, kHeight, LayerOrder::FrontToBack, shape), frontToBack));
    EXPECT_EQ(frontToBack.samplesCovered, kOverdrawLayers * pixels);
    EXPECT_EQ(frontToBack.depthTestsPassed, pixels);
    // The nearest layer, drawn first, is what remains.
    EXPECT_FLOAT_EQ(fb.depth(kWidth / 2, kHeight / 2), 0.5f * overdrawLayerNdcZ(0) + 0.5f);

    ASSERT_TRUE(renderW3Frame(
        fb, overdrawLayers(kWidth, kHeight, LayerOrder::BackToFront, shape), backToFront));
    EXPECT_EQ(backToFront.samplesCovered, kOverdrawLayers * pixels);
    EXPECT_EQ(backToFront.depthTestsPassed, kOverdrawLayers * pixels);
    EXPECT_FLOAT_EQ(fb.depth(kWidth / 2, kHeight / 2), 0.5f * overdrawLayerNdcZ(0) + 0.5f);
  }
}

TEST(Workloads, NormalizedDeviceCoordinatesMapBackToTheWindowPositions) {
  WindowGeometry g;
  g.vertices = {{{0.0f, 0.0f, 0.5f}}, {{float(kWidth), float(kHeight), 0.0f}}};
  const std::vector<glm::vec3> ndc = toNormalizedDeviceCoordinates(g, kWidth, kHeight);
  // Window y points down, GL's NDC y up: the top-left corner is NDC (-1, 1).
  EXPECT_EQ(ndc[0], glm::vec3(-1.0f, 1.0f, 0.0f));
  EXPECT_EQ(ndc[1], glm::vec3(1.0f, -1.0f, -1.0f));
}

}  // namespace
}  // namespace rast::workloads
