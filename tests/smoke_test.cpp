#include <gtest/gtest.h>

#include "pipeline/draw.h"
#include "scene/scene.h"

namespace rast {

TEST(DefaultScene, RendersSomething) {
  Framebuffer fb(320, 180, true);
  PipelineState state;
  state.viewport = {0, 0, 320, 180};
  PipelineStatistics stats;
  ASSERT_TRUE(renderScene(defaultScene(), fb, state, ShadingMode::Lambert, stats));
  EXPECT_GT(stats.fragmentsWritten, 20000u);
}

}  // namespace rast
