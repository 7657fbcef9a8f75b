// Outputs do not depend on how a draw runs: colour, depth, count images and statistics are bit
// identical for 1, 2 and 4 threads, for every coverage kernel and for both back-end targets.
#include <gtest/gtest.h>

#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/draw.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/lambert.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/window_space.h"
#include "tests/window_draw.h"

namespace rast {
namespace {

struct Frame {
  std::vector<PackedColor> color;
  std::vector<float> depth;
  std::vector<uint32_t> counts;
  PipelineStatistics stats;
};

void expectIdentical(const Frame& a, const Frame& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_TRUE(a.color == b.color);
  // Compared as bits: float == would call -0 and 0 equal.
  ASSERT_EQ(a.depth.size(), b.depth.size());
  EXPECT_EQ(std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)), 0);
  EXPECT_TRUE(a.counts == b.counts);
  EXPECT_EQ(a.stats, b.stats);
}

// W1: the Stanford bunny, framed by the workloads' camera, Lambert shading, depth less. With
// `msaaAndBlend`: 8 samples per pixel and alpha blending at a quarter of the size.
Frame renderBunny(const Mesh& mesh, const ExecutionOptions& exec, bool msaaAndBlend = false) {
  const int kW = msaaAndBlend ? 480 : 1920, kH = msaaAndBlend ? 270 : 1080;
  Framebuffer fb(kW, kH, true, msaaAndBlend ? 8 : 1);
  fb.clear(glm::vec4(0, 0, 0, 1), 1.0f);
  PipelineState state;
  state.viewport = {0, 0, kW, kH};
  if (msaaAndBlend) {
    state.blend = BlendState::alphaBlend();
    state.depth.compare = CompareOp::LessEqual;
  }
  const Camera camera = frameMesh(mesh);
  const WorldNormalVertexShader vs{glm::mat4(1.0f), camera.viewProjection(float(kW) / kH)};
  const LambertShader ps{glm::vec3(0.85f, 0.8f, 0.7f), glm::vec3(0.08f), camera.eye * 2.0f,
                         glm::vec3(1.0f)};
  Frame f;
  EXPECT_TRUE(draw(fb, state, DrawCall<WorldNormalVertexShader, LambertShader>{
                                  mesh.vertices, mesh.indices, vs, ps},
                   f.stats, exec));
  f.color = fb.colorPlane();
  f.depth = fb.depthPlane();
  f.counts = fb.countPlane();
  return f;
}

// W3: 16 full-screen layers of two triangles in one draw, front to back or back to front.
Frame renderLayers(bool frontToBack, const ExecutionOptions& exec) {
  constexpr int kW = 1920, kH = 1080;
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
  for (int i = 0; i < 16; ++i) {
    const int layer = frontToBack ? i : 15 - i;
    const float z = 0.5f * (-0.9f + 1.8f * float(layer) / 15.0f) + 0.5f;
    const uint32_t base = uint32_t(vertices.size());
    for (glm::vec2 p : {glm::vec2(0, 0), glm::vec2(kW, 0), glm::vec2(kW, kH), glm::vec2(0, kH)})
      vertices.push_back({glm::vec3(p, z)});
    for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + k);
  }
  const testing_support::DrawnFrame d = testing_support::drawWindowTriangles(
      kW, kH, vertices, indices, glm::vec4(0.2f, 0.4f, 0.6f, 1.0f), exec, true);
  return {d.color, d.depth, d.counts, d.stats};
}

ExecutionOptions withThreads(int threads) {
  ExecutionOptions e;
  e.threads = threads;
  return e;
}

TEST(ParallelExecution, BunnyIdenticalForOneTwoAndFourThreads) {
  Mesh mesh;
  ASSERT_TRUE(loadObj(std::string(RASTER_SHARED_MESHES) + "/bunny.obj", mesh));
  const Frame one = renderBunny(mesh, withThreads(1));
  // The frame is the workload, not an empty image: the peer rasterizes 777,348 samples here.
  EXPECT_GT(one.stats.samplesCovered, 700000u);
  expectIdentical(one, renderBunny(mesh, withThreads(2)), "2 threads");
  expectIdentical(one, renderBunny(mesh, withThreads(4)), "4 threads");
}

TEST(ParallelExecution, LayersIdenticalForOneTwoAndFourThreads) {
  for (bool frontToBack : {true, false}) {
    const Frame one = renderLayers(frontToBack, withThreads(1));
    EXPECT_EQ(one.stats.samplesCovered, 16u * 1920 * 1080);
    EXPECT_EQ(one.stats.fragmentsWritten, frontToBack ? 1920u * 1080 : 16u * 1920 * 1080);
    expectIdentical(one, renderLayers(frontToBack, withThreads(2)), "2 threads");
    expectIdentical(one, renderLayers(frontToBack, withThreads(4)), "4 threads");
  }
}

TEST(ParallelExecution, MultisampledBlendedBunnyIdenticalForThreadsAndKernels) {
  Mesh mesh;
  ASSERT_TRUE(loadObj(std::string(RASTER_SHARED_MESHES) + "/bunny.obj", mesh));
  ExecutionOptions reference;
  reference.threads = 1;
  ASSERT_TRUE(findCoverageKernel("scalar", reference.coverage));
  const Frame expected = renderBunny(mesh, reference, true);
  EXPECT_GT(expected.stats.samplesBlended, 0u);
  expectIdentical(expected, renderBunny(mesh, withThreads(2), true), "2 threads");
  expectIdentical(expected, renderBunny(mesh, withThreads(4), true), "4 threads");
  for (const CoverageKernel& kernel : availableCoverageKernels()) {
    ExecutionOptions exec;
    exec.coverage = kernel;
    expectIdentical(expected, renderBunny(mesh, exec, true), kernel.name);
  }
}

// The tile loop compiled for the x86-64 baseline and for AVX2 (BackEndTarget): the same bits.
TEST(ParallelExecution, BaselineAndAvx2BackEndsIdentical) {
  if (!cpuHasAvx2BackEnd()) GTEST_SKIP() << "this CPU runs only the baseline back end";
  Mesh mesh;
  ASSERT_TRUE(loadObj(std::string(RASTER_SHARED_MESHES) + "/bunny.obj", mesh));
  ExecutionOptions baseline;
  baseline.backEnd = BackEndTarget::Baseline;
  for (const bool msaaAndBlend : {false, true})
    expectIdentical(renderBunny(mesh, baseline, msaaAndBlend), renderBunny(mesh, {}, msaaAndBlend),
                    msaaAndBlend ? "bunny, 8 samples, blended" : "bunny");
  for (const bool frontToBack : {true, false})
    expectIdentical(renderLayers(frontToBack, baseline), renderLayers(frontToBack, {}),
                    frontToBack ? "layers front to back" : "layers back to front");
}

TEST(ParallelExecution, BunnyIdenticalForEveryCoverageKernel) {
  Mesh mesh;
  ASSERT_TRUE(loadObj(std::string(RASTER_SHARED_MESHES) + "/bunny.obj", mesh));
  ExecutionOptions reference;
  ASSERT_TRUE(findCoverageKernel("scalar", reference.coverage));
  const Frame expected = renderBunny(mesh, reference);
  for (const CoverageKernel& kernel : availableCoverageKernels()) {
    ExecutionOptions exec;
    exec.coverage = kernel;
    expectIdentical(expected, renderBunny(mesh, exec), kernel.name);
  }
}

}  // namespace
}  // namespace rast
