// Triangles that cover a few pixels of a tile have their depth computed and tested pixel by pixel
// (tile_loop.h, fewPixels) when a SIMD coverage kernel runs; the scalar reference kernel keeps
// the lane path. Whole draws of small triangles must give the same colour, depth bits, counts and
// statistics both ways, for every ordered compare op (and one that is not), every depth format,
// both fixed-point precisions, and a second pass over the first's depths (where Equal and the
// "or equal" ops pass on ties).
#include <gtest/gtest.h>

#include <random>

#include "pipeline/draw.h"
#include "rasterizer/coverage_kernels.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"
#include "tests/window_draw.h"

namespace rast {
namespace {

struct Pass {
  CompareOp first, second;
  float clearDepth;
};

// Mostly triangles of one to a few pixels, one in ten of 40 pixels across; depths in [0, 1].
void smallTriangles(int width, int height, std::vector<WindowVertex>& vertices,
                    std::vector<uint32_t>& indices) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 12000; ++i) {
    const float size = i % 10 == 0 ? 40.0f : (i % 3 == 0 ? 5.0f : 1.6f);
    const float cx = unit(rng) * float(width), cy = unit(rng) * float(height);
    const float z = 0.9f * unit(rng);
    for (int k = 0; k < 3; ++k) {
      indices.push_back(uint32_t(vertices.size()));
      vertices.push_back({glm::vec3(cx + size * (unit(rng) - 0.5f), cy + size * (unit(rng) - 0.5f),
                                    z + 0.1f * unit(rng))});
    }
  }
}

testing_support::DrawnFrame drawTwice(const Pass& pass, DepthFormat depthFormat,
                                      FixedPointFormat format, const CoverageKernel& kernel,
                                      const std::vector<WindowVertex>& vertices,
                                      const std::vector<uint32_t>& indices, int width, int height) {
  Framebuffer fb(width, height, /*counts=*/true);
  fb.clear(glm::vec4(0, 0, 0, 1), pass.clearDepth);
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.positionSpace = PositionSpace::Window;
  state.format = format;
  state.depth.write = true;
  state.depth.format = depthFormat;
  ExecutionOptions exec;
  exec.coverage = kernel;
  const WindowSpaceVertexShader vs;
  testing_support::DrawnFrame f;
  int n = 0;
  for (CompareOp op : {pass.first, pass.second}) {
    state.depth.compare = op;
    const ConstantColorShader ps{glm::vec4(0.2f, 0.5f, float(n++), 1.0f)};
    EXPECT_TRUE(draw(fb, state,
                     DrawCall<WindowSpaceVertexShader, ConstantColorShader>{vertices, indices, vs,
                                                                            ps},
                     f.stats, exec));
  }
  f.color = fb.colorPlane();
  f.depth = fb.depthPlane();
  f.counts = fb.countPlane();
  return f;
}

TEST(FewPixelDepth, SmallTriangleDrawsMatchTheScalarKernel) {
  constexpr int kWidth = 197, kHeight = 131;
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
  smallTriangles(kWidth, kHeight, vertices, indices);
  CoverageKernel scalar;
  ASSERT_TRUE(findCoverageKernel("scalar", scalar));
  using enum CompareOp;
  const Pass passes[] = {{Less, Less, 1.0f},          {LessEqual, LessEqual, 1.0f},
                         {Greater, Greater, 0.0f},    {GreaterEqual, GreaterEqual, 0.0f},
                         {Less, Equal, 1.0f},         {Less, NotEqual, 1.0f}};
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()})
    for (const DepthFormat depthFormat :
         {DepthFormat::Float32, DepthFormat::Unorm24, DepthFormat::Unorm16})
      for (const Pass& pass : passes) {
        SCOPED_TRACE(testing::Message() << format.name() << ", depth format " << int(depthFormat)
                                        << ", ops " << int(pass.first) << " then "
                                        << int(pass.second));
        const testing_support::DrawnFrame expected =
            drawTwice(pass, depthFormat, format, scalar, vertices, indices, kWidth, kHeight);
        // Both outcomes of the test occur often, in both passes together.
        EXPECT_GT(expected.stats.depthTestsPassed, 5000u);
        EXPECT_GT(expected.stats.depthTestsFailed, 5000u);
        for (const CoverageKernel& kernel : availableCoverageKernels()) {
          if (kernel.simd == nullptr) continue;
          SCOPED_TRACE(kernel.name);
          EXPECT_TRUE(testing_support::sameFrame(
              drawTwice(pass, depthFormat, format, kernel, vertices, indices, kWidth, kHeight),
              expected));
        }
      }
}

}  // namespace
}  // namespace rast
