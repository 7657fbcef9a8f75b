// Identities the pipeline statistics must satisfy on real renders, the clipper's per-plane
// counters on hand-made triangles, and the instrumentation (stage times, bin capture) leaving
// every counter and pixel unchanged.
#include <gtest/gtest.h>

#include <cstring>
#include <numeric>

#include "debug/statistics_table.h"
#include "pipeline/draw.h"
#include "scene/frame.h"
#include "scene/scene_file.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"
#include "window_draw.h"

namespace rast {
namespace {

SceneDescription smallDefaultScene(CullMode cull) {
  PipelineState state;
  state.viewport = {0, 0, 240, 135};
  state.cullMode = cull;
  return describeScene(defaultScene(), state, ShadingMode::Lambert);
}

void expectIdentities(const PipelineStatistics& s, const std::string& what) {
  SCOPED_TRACE(what);
  // Every triangle leaving the clipper is dropped at setup for one reason, or set up.
  EXPECT_EQ(s.clipOutputTriangles, s.clipDegenerate + s.setupCulledBack + s.setupCulledFront +
                                       s.setupZeroArea + s.setupNoSamples + s.setupTriangles);
  // Nothing here crosses a clip plane, so every triangle in is accounted for exactly once.
  ASSERT_EQ(s.clipClipped, 0u);
  EXPECT_EQ(s.inputTriangles, s.clipNonFinite + s.clipTrivialReject + s.clipOutputTriangles);
  EXPECT_EQ(s.inputTriangles, s.clipNonFinite + s.clipTrivialReject + s.clipDegenerate +
                                  s.setupCulledBack + s.setupCulledFront + s.setupZeroArea +
                                  s.setupNoSamples + s.setupTriangles);
  // Opaque shaders with early depth: each covered sample is shaded or fails early depth.
  EXPECT_EQ(s.samplesCovered, s.pixelShaderInvocations + s.depthTestsFailed);
  EXPECT_EQ(s.depthTestsPassed, s.pixelShaderInvocations);
  EXPECT_EQ(s.fragmentsWritten, s.pixelShaderInvocations);
  EXPECT_EQ(s.fragmentsDiscarded, 0u);
  EXPECT_EQ(s.inputIndices, 3 * s.inputTriangles);
  EXPECT_LE(s.vertexShaderInvocations, s.inputIndices);
}

TEST(PipelineStatistics, IdentitiesHoldPerDrawAndPerFrame) {
  for (CullMode cull : {CullMode::None, CullMode::Back, CullMode::Front}) {
    const SceneDescription scene = smallDefaultScene(cull);
    const FramePlan plan = planFrame(scene, scene.camera);
    Framebuffer fb(scene.width, scene.height, true);
    FrameRecord record;
    ASSERT_TRUE(renderFrame(plan, fb, record).isOk());
    PipelineStatistics sum;
    for (const DrawRecord& d : record.draws) {
      expectIdentities(d.stats, d.label + " cull " + cullModeName(cull));
      sum += d.stats;
    }
    EXPECT_EQ(sum, record.total);
    expectIdentities(record.total, std::string("frame, cull ") + cullModeName(cull));
    const uint64_t written = std::accumulate(fb.countPlane().begin(), fb.countPlane().end(), uint64_t{0});
    EXPECT_EQ(written, record.total.fragmentsWritten);
    if (cull == CullMode::Back) {
      EXPECT_GT(record.total.setupCulledBack, 0u);
    }
    if (cull == CullMode::Front) {
      EXPECT_GT(record.total.setupCulledFront, 0u);
    }
    // Early depth placed as the state says: all of these draws test early.
    const DerivedCounters derived = deriveCounters(record.total, plan.draws[0].state, false);
    EXPECT_EQ(derived.earlyDepthFailed, record.total.depthTestsFailed);
    EXPECT_EQ(derived.lateDepthFailed, 0u);
    EXPECT_EQ(derived.vertexCacheHits, record.total.inputIndices - record.total.vertexShaderInvocations);
  }
}

TEST(PipelineStatistics, LateDepthIsCountedAsLate) {
  SceneDescription scene = smallDefaultScene(CullMode::None);
  for (DrawSpec& d : scene.draws) d.state.depth.early = false;
  FramePlan plan = planFrame(scene, scene.camera);
  Framebuffer fb(scene.width, scene.height);
  FrameRecord record;
  ASSERT_TRUE(renderFrame(plan, fb, record).isOk());
  const PipelineStatistics& s = record.total;
  // Every covered sample is shaded, then tested.
  EXPECT_EQ(s.pixelShaderInvocations, s.samplesCovered);
  EXPECT_EQ(s.depthTestsPassed + s.depthTestsFailed, s.samplesCovered);
  EXPECT_GT(s.depthTestsFailed, 0u);
  const nlohmann::ordered_json j = statisticsJson(record);
  EXPECT_EQ(j["derived"]["merge.late_depth_failed"].get<uint64_t>(), s.depthTestsFailed);
  EXPECT_EQ(j["derived"]["merge.early_depth_failed"].get<uint64_t>(), 0u);
}

TEST(PipelineStatistics, InstrumentationChangesNothing) {
  const SceneDescription scene = smallDefaultScene(CullMode::Back);
  const FramePlan plan = planFrame(scene, scene.camera);
  auto render = [&](int threads, bool instrumented, PipelineStatistics& stats, Framebuffer& fb,
                    std::vector<uint32_t>& bins) {
    fb.clear(plan.background, plan.clearDepth);
    for (const FrameDraw& d : plan.draws) {
      ExecutionOptions exec;
      exec.threads = threads;
      StageTimings timings;
      DrawCapture capture;
      if (instrumented) {
        exec.timings = &timings;
        exec.capture = &capture;
      }
      ASSERT_TRUE(d.run(fb, d.state, PixelPass::Scene, 0, stats, exec).isOk());
      if (instrumented) {
        EXPECT_GT(timings.total(), 0.0);
        EXPECT_EQ(std::accumulate(capture.binEntries.begin(), capture.binEntries.end(), uint64_t{0}),
                  [&] {
                    PipelineStatistics one;
                    Framebuffer scratch(scene.width, scene.height);
                    scratch.clear(plan.background, plan.clearDepth);
                    (void)d.run(scratch, d.state, PixelPass::Scene, 0, one, {});
                    return one.binEntries;
                  }());
        bins.resize(capture.binEntries.size());
        for (size_t t = 0; t < bins.size(); ++t) bins[t] += capture.binEntries[t];
      }
    }
  };
  PipelineStatistics plain, timed1, timed2;
  Framebuffer a(scene.width, scene.height), b(scene.width, scene.height), c(scene.width, scene.height);
  std::vector<uint32_t> none, bins1, bins2;
  render(1, false, plain, a, none);
  render(1, true, timed1, b, bins1);
  render(2, true, timed2, c, bins2);
  EXPECT_EQ(plain, timed1);
  EXPECT_EQ(plain, timed2);
  EXPECT_TRUE(a.colorPlane() == b.colorPlane() && a.colorPlane() == c.colorPlane());
  EXPECT_EQ(std::memcmp(a.depthPlane().data(), c.depthPlane().data(), a.depthPlane().size() * sizeof(float)), 0);
  EXPECT_EQ(bins1, bins2);
  EXPECT_EQ(std::accumulate(bins1.begin(), bins1.end(), uint64_t{0}), plain.binEntries);
}

// Clip-space positions straight through.
struct ClipSpaceVertex {
  glm::vec4 position;
};
struct ClipSpaceShader {
  using Vertex = ClipSpaceVertex;
  static constexpr int kVaryings = 0;
  ShadedVertex<0> operator()(const Vertex& v) const { return {v.position, {}}; }
};

PipelineStatistics drawClipSpace(const std::vector<ClipSpaceVertex>& v, PipelineState state) {
  Framebuffer fb(64, 64);
  fb.clear(glm::vec4(0), 1.0f);
  state.viewport = {0, 0, 64, 64};
  std::vector<uint32_t> indices(v.size());
  std::iota(indices.begin(), indices.end(), 0u);
  PipelineStatistics stats;
  const ClipSpaceShader vs;
  const ConstantColorShader ps;
  EXPECT_TRUE(draw(fb, state, DrawCall<ClipSpaceShader, ConstantColorShader>{v, indices, vs, ps}, stats).isOk());
  return stats;
}

uint64_t sumOfPlaneCounters(const PipelineStatistics& s) {
  uint64_t sum = 0;
  for (const auto& [in, out] : kClipPlaneCounters) sum += s.*in + s.*out;
  return sum;
}

TEST(PipelineStatistics, ClipperCountsPolygonsPerPlane) {
  // One vertex in front of the near plane (z/w = -2): cut by the near plane only, into a quad.
  const PipelineStatistics near = drawClipSpace(
      {{{0, 0, -2, 1}}, {{0.5f, 0, 0, 1}}, {{0, 0.5f, 0, 1}}}, PipelineState{});
  EXPECT_EQ(near.clipClipped, 1u);
  EXPECT_EQ(near.clipNearIn, 1u);
  EXPECT_EQ(near.clipNearOut, 1u);
  EXPECT_EQ(sumOfPlaneCounters(near), 2u);
  EXPECT_EQ(near.clipOutputTriangles, 2u);
  // One vertex beyond the far plane.
  const PipelineStatistics far = drawClipSpace(
      {{{0, 0, 3, 1}}, {{0.5f, 0, 0, 1}}, {{0, 0.5f, 0, 1}}}, PipelineState{});
  EXPECT_EQ(far.clipFarIn, 1u);
  EXPECT_EQ(far.clipFarOut, 1u);
  EXPECT_EQ(sumOfPlaneCounters(far), 2u);
  // One vertex behind the eye (w < 0): cut by w >= 0 first, then by the near plane.
  const PipelineStatistics behind = drawClipSpace(
      {{{0, 0, 0.5f, -1}}, {{0.5f, 0, 0, 1}}, {{0, 0.5f, 0, 1}}}, PipelineState{});
  EXPECT_EQ(behind.clipWIn, 1u);
  EXPECT_EQ(behind.clipWOut, 1u);
  EXPECT_EQ(behind.clipNearIn, 1u);
  EXPECT_EQ(behind.clipNearOut, 1u);
  // Window space, one vertex beyond the 16.8 guard band on the left (16,384 pixels) and one
  // below it: cut by those two planes.
  PipelineState window;
  window.positionSpace = PositionSpace::Window;
  window.format = FixedPointFormat::d16_8();
  const PipelineStatistics guard = drawClipSpace(
      {{{-20000, 10, 0.5f, 1}}, {{40, 30000, 0.5f, 1}}, {{40, 10, 0.5f, 1}}}, window);
  EXPECT_EQ(guard.clipGuardLeftIn, 1u);
  EXPECT_EQ(guard.clipGuardLeftOut, 1u);
  EXPECT_EQ(guard.clipGuardBottomIn, 1u);
  EXPECT_EQ(guard.clipGuardBottomOut, 1u);
  EXPECT_EQ(sumOfPlaneCounters(guard), 4u);
  EXPECT_GT(guard.fragmentsWritten, 0u);
  // Inside everything: no plane counts.
  const PipelineStatistics inside = drawClipSpace(
      {{{0, 0, 0, 1}}, {{0.5f, 0, 0, 1}}, {{0, 0.5f, 0, 1}}}, PipelineState{});
  EXPECT_EQ(inside.clipClipped, 0u);
  EXPECT_EQ(sumOfPlaneCounters(inside), 0u);
}

TEST(StatisticsTable, AlignedColumnsAndAllZeroRowsLeftOut) {
  const SceneDescription scene = smallDefaultScene(CullMode::Back);
  Framebuffer fb(scene.width, scene.height);
  FrameRecord record;
  ASSERT_TRUE(renderFrame(planFrame(scene, scene.camera), fb, record).isOk());
  const std::string table = statisticsTable(record);
  EXPECT_EQ(table.rfind("counter ", 0), 0u) << table;
  EXPECT_NE(table.find("setup.culled_back"), std::string::npos);
  EXPECT_EQ(table.find("clip.near_in"), std::string::npos);  // zero everywhere here
  EXPECT_NE(table.find("counters are zero in every column and not shown"), std::string::npos);
  EXPECT_NE(table.find("back_end"), std::string::npos);
  // Every line of the counter table is as long as the header.
  const size_t width = table.find('\n');
  size_t start = width + 1;
  for (int line = 0; line < 10; ++line) {
    const size_t end = table.find('\n', start);
    EXPECT_EQ(end - start, width) << table.substr(start, end - start);
    start = end + 1;
  }
  const nlohmann::ordered_json j = statisticsJson(record);
  EXPECT_EQ(j["setup.triangles"].get<uint64_t>(), record.total.setupTriangles);
  ASSERT_EQ(j["draws"].size(), 3u);
  uint64_t culled = 0;
  for (const auto& d : j["draws"]) culled += d["counters"]["setup.culled_back"].get<uint64_t>();
  EXPECT_EQ(culled, record.total.setupCulledBack);
}

// A draw of three chunks of triangles is binned while setting up at one thread and in a pass of
// its own at two (fewer than two chunks a thread): the timings say which, and the two paths draw
// the same frame. The statistics table and JSON say which draws' clip_setup includes binning.
TEST(StageTimings, SayWhichDrawsBinnedWhileSettingUp) {
  const int width = 203, height = 157;
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
  // Three chunks of triangles of a few pixels over the window, overlapping at different depths.
  for (uint32_t t = 0; t < uint32_t(3 * SetupTriangles<0>::kInputChunk - 1); ++t) {
    const float x = float(t * 37 % (width - 6)), y = float(t * 53 % (height - 6));
    const float z = float(t % 97) / 97.0f;
    const uint32_t base = uint32_t(vertices.size());
    vertices.push_back({glm::vec3(x, y, z)});
    vertices.push_back({glm::vec3(x + 5.5f, y + 1.25f, z)});
    vertices.push_back({glm::vec3(x + 2.0f, y + 4.75f, z)});
    for (uint32_t k : {0u, 1u, 2u}) indices.push_back(base + k);
  }
  testing_support::DrawnFrame frames[2];
  for (const int threads : {1, 2}) {
    StageTimings timings;
    ExecutionOptions exec;
    exec.threads = threads;
    exec.timings = &timings;
    frames[threads - 1] = testing_support::drawWindowTriangles(
        width, height, vertices, indices, glm::vec4(0.3f, 0.5f, 0.7f, 1.0f), exec, true);
    EXPECT_EQ(timings.drawsBinnedInSetup, threads == 1 ? 1u : 0u) << threads << " threads";
  }
  EXPECT_TRUE(testing_support::sameFrame(frames[0], frames[1]));
  EXPECT_GT(frames[0].stats.fragmentsWritten, 50000u);

  const SceneDescription scene = smallDefaultScene(CullMode::Back);
  Framebuffer fb(scene.width, scene.height);
  FrameRecord record;
  ExecutionOptions oneThread;
  oneThread.threads = 1;
  ASSERT_TRUE(renderFrame(planFrame(scene, scene.camera), fb, record, oneThread).isOk());
  const uint64_t binnedInSetup = record.timings.drawsBinnedInSetup;
  const std::string note = "clip_setup includes binning in ";
  EXPECT_EQ(statisticsTable(record).find(note) != std::string::npos, binnedInSetup > 0);
  EXPECT_EQ(statisticsJson(record)["draws_binned_in_setup"].get<uint64_t>(), binnedInSetup);
  record.timings.drawsBinnedInSetup = 2;
  EXPECT_NE(statisticsTable(record).find(note + "2 draws"), std::string::npos);
}

}  // namespace
}  // namespace rast
