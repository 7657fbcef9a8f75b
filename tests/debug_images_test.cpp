// The debugging images on hand-counted cases: per-tile bin entries, per-pixel overdraw, triangle
// ids, the stage that decided each pixel, and the coverage masks of the zoomed tile; and the
// colours that stand for those numbers.
#include <gtest/gtest.h>

#include <bit>

#include "debug/color_scale.h"
#include "debug/debug_images.h"
#include "scene/frame.h"

namespace rast {
namespace {

void addTriangle(std::vector<WindowVertex>& v, glm::vec2 a, glm::vec2 b, glm::vec2 c, float z) {
  for (glm::vec2 p : {a, b, c}) v.push_back({{p.x, p.y, z}});
}

// Two triangles of one quad [x0, x1) x [y0, y1), front-facing (counter-clockwise on the image),
// or back-facing.
void addQuad(std::vector<WindowVertex>& v, float x0, float y0, float x1, float y1, float z,
             bool front = true) {
  if (front) {
    addTriangle(v, {x0, y0}, {x0, y1}, {x1, y0}, z);
    addTriangle(v, {x1, y0}, {x0, y1}, {x1, y1}, z);
  } else {
    addTriangle(v, {x0, y0}, {x1, y0}, {x0, y1}, z);
    addTriangle(v, {x1, y0}, {x1, y1}, {x0, y1}, z);
  }
}

DebugData capture(const std::vector<WindowVertex>& v, const PipelineState& state, int w, int h,
                  std::optional<std::pair<int, int>> tile = std::nullopt) {
  DebugData d;
  const Status s = captureDebugData(planTriangleList(v, state, ShadingMode::Constant, w, h), tile, {}, d);
  EXPECT_TRUE(s.isOk()) << s.message();
  return d;
}

PipelineState windowState(int w, int h) {
  PipelineState s;
  s.viewport = {0, 0, w, h};
  s.positionSpace = PositionSpace::Window;
  return s;
}

// A 16x16 square as two triangles split along the diagonal from (16, 0) to (0, 16): the upper
// left triangle is binned to tiles (0,0), (1,0), (0,1) and the corner test rejects (1,1) (every
// corner sample has x + y > 16); the lower right one is binned to (1,0), (0,1), (1,1).
TEST(DebugImages, BinEntriesPerTileAreHandCounted) {
  std::vector<WindowVertex> v;
  addTriangle(v, {0, 0}, {0, 16}, {16, 0}, 0.5f);
  addTriangle(v, {16, 0}, {0, 16}, {16, 16}, 0.5f);
  const DebugData d = capture(v, windowState(16, 16), 16, 16);
  ASSERT_EQ(d.tilesX, 2);
  ASSERT_EQ(d.tilesY, 2);
  EXPECT_EQ(d.binEntries, (std::vector<uint32_t>{1, 2, 2, 1}));
  // Shared edge, top-left rule: every pixel written exactly once. Samples with x + y = 15 lie on
  // the diagonal, a right edge of the first triangle, so the second owns them.
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const size_t p = size_t(y * 16 + x);
      EXPECT_EQ(d.overdraw[p], 1u) << x << "," << y;
      EXPECT_EQ(d.triangleIds[p], x + y < 15 ? 0 : 1) << x << "," << y;
      EXPECT_EQ(d.stages[p], PixelStage::Shaded);
    }
  // The busiest tile (the first with two entries) is zoomed: both triangles, complementary masks.
  EXPECT_EQ(d.zoomTileX, 1);
  EXPECT_EQ(d.zoomTileY, 0);
  ASSERT_EQ(d.zoomTriangles.size(), 2u);
  EXPECT_EQ(d.zoomTriangles[0].triangleId, 0u);
  EXPECT_EQ(d.zoomTriangles[1].triangleId, 1u);
  EXPECT_EQ(std::popcount(d.zoomTriangles[0].mask), 28);  // x + y < 15 with x >= 8: 7 + 6 + ... + 0
  EXPECT_EQ(std::popcount(d.zoomTriangles[1].mask), 36);
  EXPECT_EQ(d.zoomTriangles[0].mask & d.zoomTriangles[1].mask, 0u);
  EXPECT_EQ(d.zoomTriangles[0].mask | d.zoomTriangles[1].mask, kFullMask);
  // Bit (x, y) of tile (1, 0) is pixel (8 + x, y).
  EXPECT_TRUE(d.zoomTriangles[0].mask & (CoverageMask{1} << coverageBit(6, 0)));   // pixel 14,0
  EXPECT_FALSE(d.zoomTriangles[0].mask & (CoverageMask{1} << coverageBit(7, 0)));  // 15,0: x+y=15
}

TEST(DebugImages, ZoomOnAChosenTileAndOutsideTheFrame) {
  std::vector<WindowVertex> v;
  addTriangle(v, {0, 0}, {0, 16}, {16, 0}, 0.5f);
  addTriangle(v, {16, 0}, {0, 16}, {16, 16}, 0.5f);
  const DebugData d = capture(v, windowState(16, 16), 16, 16, std::make_pair(1, 1));
  ASSERT_EQ(d.zoomTriangles.size(), 1u);
  EXPECT_EQ(d.zoomTriangles[0].triangleId, 1u);
  EXPECT_EQ(d.zoomTriangles[0].mask, kFullMask);
  DebugData none;
  const Status s = captureDebugData(planTriangleList(v, windowState(16, 16), ShadingMode::Constant, 16, 16),
                                    std::make_pair(2, 0), {}, none);
  EXPECT_EQ(s.message(), "tile 2,0 is outside the 2x2 tiles of the frame");
}

// Overdraw with depth "always": two overlapping rectangles, [0, 8) and [4, 12) wide, full height.
TEST(DebugImages, OverdrawCountsEveryWrittenFragment) {
  std::vector<WindowVertex> v;
  addQuad(v, 0, 0, 8, 16, 0.5f);
  addQuad(v, 4, 0, 12, 16, 0.25f);
  PipelineState state = windowState(16, 16);
  state.depth.compare = CompareOp::Always;
  const DebugData d = capture(v, state, 16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const uint32_t expected = (x < 8 ? 1 : 0) + (x >= 4 && x < 12 ? 1 : 0);
      EXPECT_EQ(d.overdraw[size_t(y * 16 + x)], expected) << x << "," << y;
    }
  // The later rectangle wins where they overlap (ids 2 and 3 are its triangles).
  EXPECT_GE(d.triangleIds[5], 2);
  EXPECT_LT(d.triangleIds[2], 2);
  EXPECT_EQ(d.triangleIds[13], -1);
}

// One quadrant each: shaded (near quad), failed depth (a quad at depth 1 against a clear of 1,
// compare less), culled (a back-facing quad, cull back) and not covered.
TEST(DebugImages, StageImageSaysWhichStageDecidedEachPixel) {
  std::vector<WindowVertex> v;
  addQuad(v, 0, 0, 8, 8, 0.5f);
  addQuad(v, 8, 0, 16, 8, 1.0f);
  addQuad(v, 0, 8, 8, 16, 0.5f, false);
  PipelineState state = windowState(16, 16);
  state.cullMode = CullMode::Back;
  const DebugData d = capture(v, state, 16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const PixelStage expected = y < 8 ? (x < 8 ? PixelStage::Shaded : PixelStage::FailedDepth)
                                        : (x < 8 ? PixelStage::Culled : PixelStage::NotCovered);
      EXPECT_EQ(d.stages[size_t(y * 16 + x)], expected) << x << "," << y;
    }
  const RgbImage image = stageImage(d);
  const int k = image.width / 16;
  ASSERT_EQ(image.width, 16 * k);
  EXPECT_EQ(image.at(2 * k, 2 * k), stageColor(PixelStage::Shaded));
  EXPECT_EQ(image.at(10 * k, 2 * k), stageColor(PixelStage::FailedDepth));
  EXPECT_EQ(image.at(2 * k, 10 * k), stageColor(PixelStage::Culled));
  EXPECT_EQ(image.at(10 * k, 10 * k), stageColor(PixelStage::NotCovered));
}

TEST(DebugImages, HeatMapColoursFollowTheCounts) {
  std::vector<WindowVertex> v;
  addTriangle(v, {0, 0}, {0, 16}, {16, 0}, 0.5f);
  addTriangle(v, {16, 0}, {0, 16}, {16, 16}, 0.5f);
  const DebugData d = capture(v, windowState(16, 16), 16, 16);
  const RgbImage heat = binHeatMapImage(d);
  const int k = enlargementFor(16, 16);
  ASSERT_EQ(heat.width, 16 * k);
  ASSERT_GT(heat.height, 16 * k);  // the legend below
  // Counts 1..2: 1 at the bottom of the scale, 2 (the maximum) at the top.
  EXPECT_EQ(heat.at(4 * k, 4 * k), viridis(0.0));
  EXPECT_EQ(heat.at(12 * k, 4 * k), viridis(1.0));
  EXPECT_EQ(heat.at(4 * k, 12 * k), viridis(1.0));
  EXPECT_EQ(heat.at(12 * k, 12 * k), viridis(0.0));
}

TEST(ColorScale, ViridisGetsLighterAlongTheScale) {
  EXPECT_EQ(viridis(0.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(viridis(1.0), (Rgb{253, 231, 37}));
  EXPECT_EQ(viridis(-3.0), viridis(0.0));
  EXPECT_EQ(viridis(7.0), viridis(1.0));
  double previous = -1;
  for (int i = 0; i <= 64; ++i) {
    const Rgb c = viridis(i / 64.0);
    const double luma = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    EXPECT_GT(luma, previous) << i;
    previous = luma;
  }
}

TEST(ColorScale, LegendTextIsDrawn) {
  RgbImage image(40, 12);
  const int width = drawText(image, 0, 0, "10", {255, 255, 255}, 2);
  EXPECT_EQ(width, textWidth("10", 2));
  // '1' has its middle column set on every row; '0' is hollow in the middle of row 1.
  EXPECT_EQ(image.at(2, 1), (Rgb{255, 255, 255}));
  EXPECT_EQ(image.at(8 + 2, 2 * 1 + 1), (Rgb{0, 0, 0}));
  EXPECT_EQ(image.at(8, 0), (Rgb{255, 255, 255}));
}

}  // namespace
}  // namespace rast
