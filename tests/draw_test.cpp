// Draw calls: validation before anything is drawn, the post-transform cache, determinism.
#include "pipeline/draw.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <glm/glm.hpp>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "scene/mesh.h"
#include "scene/scene.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/vertex_color.h"

namespace rast {
namespace {

// Positions are clip space already; counts its own invocations.
struct CountingVS {
  using Vertex = glm::vec4;
  static constexpr int kVaryings = 1;
  std::atomic<uint64_t>* calls;

  ShadedVertex<1> operator()(const glm::vec4& p) const {
    calls->fetch_add(1, std::memory_order_relaxed);
    return {p, {p.x}};
  }
};

struct CountingPS {
  static constexpr int kVaryings = 1;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kSideEffects = true;  // runs once per passing fragment
  std::atomic<uint64_t>* calls;

  PixelResult operator()(const Fragment<1>& f) const {
    calls->fetch_add(1, std::memory_order_relaxed);
    return {glm::vec4(f.varyings[0] * 0.5f + 0.5f, 0.25f, 0.75f, 1.0f)};
  }
};

struct DrawOutcome {
  Status status = Status::ok();
  uint64_t vertexCalls = 0, pixelCalls = 0;
};

DrawOutcome drawCounting(Framebuffer& fb, const PipelineState& state,
                         const std::vector<glm::vec4>& vertices,
                         const std::vector<uint32_t>& indices, PipelineStatistics& stats) {
  std::atomic<uint64_t> vsCalls{0}, psCalls{0};
  const CountingVS vs{&vsCalls};
  const CountingPS ps{&psCalls};
  DrawOutcome out;
  out.status = draw(fb, state, DrawCall<CountingVS, CountingPS>{vertices, indices, vs, ps}, stats);
  out.vertexCalls = vsCalls.load();
  out.pixelCalls = psCalls.load();
  return out;
}

// A valid draw covering most of the viewport.
const std::vector<glm::vec4> kQuad = {
    {-0.9f, -0.9f, 0, 1}, {0.9f, -0.9f, 0, 1}, {0.9f, 0.9f, 0, 1}, {-0.9f, 0.9f, 0, 1}};
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

// ---------------------------------------------------------------------------------------------

struct InvalidCase {
  const char* name;
  PipelineState state;
  std::vector<uint32_t> indices;
  int fbWidth, fbHeight;
  std::vector<std::string> messageParts;  // the message must name the problem
};

PipelineState stateWith(Viewport vp, FixedPointFormat format = FixedPointFormat::d24_4()) {
  PipelineState s;
  s.viewport = vp;
  s.format = format;
  return s;
}

TEST(DrawValidation, ErrorsLeaveFramebufferAndStatisticsUntouched) {
  const Viewport vp{0, 0, 32, 32};
  const FixedPointFormat d16 = FixedPointFormat::d16_8();
  const std::vector<InvalidCase> cases = {
      // The bad index comes after a valid triangle: nothing at all may be drawn.
      {"index out of range",
       stateWith(vp),
       {0, 1, 2, 0, 2, 4},
       32,
       32,
       {"index 5", "value 4", "out of range", "4 vertices"}},
      {"index count 4", stateWith(vp), {0, 1, 2, 3}, 32, 32, {"index count 4", "multiple of 3"}},
      {"index count 1", stateWith(vp), {0}, 32, 32, {"index count 1", "multiple of 3"}},
      {"zero width",
       stateWith({0, 0, 0, 32}),
       kQuadIndices,
       32,
       32,
       {"viewport size 0x32", "positive"}},
      {"zero height",
       stateWith({0, 0, 32, 0}),
       kQuadIndices,
       32,
       32,
       {"viewport size 32x0", "positive"}},
      {"negative width",
       stateWith({4, 4, -8, 16}),
       kQuadIndices,
       32,
       32,
       {"viewport size -8x16", "positive"}},
      // 16.8 reaches +-2^14 = 16384 pixels.
      {"16.8 viewport 40000 wide",
       stateWith({0, 0, 40000, 32}, d16),
       kQuadIndices,
       32,
       32,
       {"40000x32", "exceeds", "16.8", "16384"}},
      {"16.8 viewport one past the range",
       stateWith({0, 0, 16385, 32}, d16),
       kQuadIndices,
       32,
       32,
       {"16385x32", "exceeds", "16.8"}},
      {"16.8 viewport starting below the range",
       stateWith({-16385, 0, 64, 32}, d16),
       kQuadIndices,
       32,
       32,
       {"-16385", "exceeds", "16.8"}},
      {"16.8 framebuffer 20000 wide",
       stateWith(vp, d16),
       kQuadIndices,
       20000,
       2,
       {"framebuffer", "exceeds", "16.8"}},
      {"9 fraction bits",
       stateWith(vp, FixedPointFormat{19, 9}),
       kQuadIndices,
       32,
       32,
       {"19.9", "not supported"}},
      {"0 fraction bits",
       stateWith(vp, FixedPointFormat{24, 0}),
       kQuadIndices,
       32,
       32,
       {"24.0", "not supported"}},
      {"29 bits",
       stateWith(vp, FixedPointFormat{25, 4}),
       kQuadIndices,
       32,
       32,
       {"25.4", "not supported"}},
      {"3 integer bits",
       stateWith(vp, FixedPointFormat{3, 4}),
       kQuadIndices,
       32,
       32,
       {"3.4", "not supported"}},
  };
  for (const InvalidCase& c : cases) {
    Framebuffer fb(c.fbWidth, c.fbHeight, true);
    fb.clear(glm::vec4(0.2f, 0.4f, 0.6f, 0.8f), 0.3f);
    std::fill(fb.countPlane().begin(), fb.countPlane().end(), 7u);
    const std::vector<PackedColor> color = fb.colorPlane();
    const std::vector<float> depth = fb.depthPlane();
    const std::vector<uint32_t> counts = fb.countPlane();
    PipelineStatistics stats;
    stats.inputTriangles = 11;  // earlier draws' totals must survive a failed draw
    stats.fragmentsWritten = 13;
    const PipelineStatistics before = stats;

    const DrawOutcome r = drawCounting(fb, c.state, kQuad, c.indices, stats);
    EXPECT_FALSE(r.status.isOk()) << c.name;
    for (const std::string& part : c.messageParts)
      EXPECT_NE(r.status.message().find(part), std::string::npos)
          << c.name << ": message '" << r.status.message() << "' lacks '" << part << "'";
    EXPECT_EQ(r.vertexCalls, 0u) << c.name;
    EXPECT_EQ(r.pixelCalls, 0u) << c.name;
    EXPECT_EQ(fb.colorPlane(), color) << c.name;
    EXPECT_EQ(fb.depthPlane(), depth) << c.name;
    EXPECT_EQ(fb.countPlane(), counts) << c.name;
    EXPECT_TRUE(stats == before) << c.name;
  }
}

// The indices' range is checked in the vertex stage's parallel first pass: in a draw of several
// chunks of indices, on any thread count, bad indices far from the start (two of them, in
// different chunks) are found before any vertex is shaded, and the message names the first.
TEST(DrawValidation, IndexOutOfRangeInALargeDrawOnEveryThreadCount) {
  constexpr uint32_t kColumns = 200;
  std::vector<glm::vec4> vertices;
  for (uint32_t i = 0; i <= kColumns; ++i)
    for (const float y : {-0.5f, 0.5f})
      vertices.push_back({-0.9f + 1.8f * float(i) / kColumns, y, 0.5f, 1.0f});
  std::vector<uint32_t> indices;
  while (indices.size() < 300'000)
    for (uint32_t i = 0; i < kColumns; ++i)
      indices.insert(indices.end(), {2 * i, 2 * i + 2, 2 * i + 1, 2 * i + 1, 2 * i + 2, 2 * i + 3});
  indices.resize(indices.size() / 3 * 3);
  const uint32_t vertexCount = uint32_t(vertices.size());
  indices[200'001] = vertexCount + 6;
  indices[123'457] = vertexCount;
  for (const int threads : {1, 2, 4}) {
    Framebuffer fb(64, 32, true);
    fb.clear(glm::vec4(0.2f, 0.4f, 0.6f, 0.8f), 0.3f);
    const std::vector<PackedColor> color = fb.colorPlane();
    const std::vector<float> depth = fb.depthPlane();
    PipelineStatistics stats;
    std::atomic<uint64_t> vsCalls{0}, psCalls{0};
    const CountingVS vs{&vsCalls};
    const CountingPS ps{&psCalls};
    ExecutionOptions exec;
    exec.threads = threads;
    const Status status = draw(fb, stateWith({0, 0, 64, 32}),
                               DrawCall<CountingVS, CountingPS>{vertices, indices, vs, ps}, stats,
                               exec);
    ASSERT_FALSE(status.isOk()) << threads << " threads";
    EXPECT_EQ(status.message(), "index 123457 has value " + std::to_string(vertexCount) +
                                    ", out of range for " + std::to_string(vertexCount) +
                                    " vertices");
    EXPECT_EQ(vsCalls.load(), 0u);
    EXPECT_EQ(psCalls.load(), 0u);
    EXPECT_EQ(fb.colorPlane(), color);
    EXPECT_EQ(fb.depthPlane(), depth);
    EXPECT_EQ(fb.countPlane(), std::vector<uint32_t>(64 * 32, 0u));
    EXPECT_TRUE(stats == PipelineStatistics{});
  }
}

// The limits themselves are valid, and the draw then renders: a quad over all of NDC covers each
// pixel of the framebuffer (inside every one of these viewports) once.
TEST(DrawValidation, LimitsAreAccepted) {
  const std::vector<glm::vec4> fullQuad = {
      {-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
  const FixedPointFormat d16 = FixedPointFormat::d16_8();
  const PipelineState states[] = {stateWith({0, 0, 16384, 32}, d16),
                                  stateWith({-16384, -16384, 32768, 32768}, d16),
                                  stateWith({0, 0, 32, 32}, FixedPointFormat{20, 8}),
                                  stateWith({0, 0, 32, 32}, FixedPointFormat{27, 1})};
  for (const PipelineState& state : states) {
    Framebuffer fb(32, 32, true);
    PipelineStatistics stats;
    const DrawOutcome r = drawCounting(fb, state, fullQuad, kQuadIndices, stats);
    EXPECT_TRUE(r.status.isOk()) << r.status.message();
    EXPECT_EQ(r.vertexCalls, 4u);
    EXPECT_EQ(stats.fragmentsWritten, 32u * 32u) << state.format.name();
    EXPECT_EQ(fb.countPlane(), std::vector<uint32_t>(32 * 32, 1u)) << state.format.name();
    EXPECT_EQ(r.pixelCalls, stats.pixelShaderInvocations);
  }
  // No indices: valid, and nothing happens.
  Framebuffer fb(8, 8, true);
  PipelineStatistics stats;
  const DrawOutcome r = drawCounting(fb, stateWith({0, 0, 8, 8}), kQuad, {}, stats);
  EXPECT_TRUE(r.status.isOk());
  EXPECT_EQ(r.vertexCalls, 0u);
  EXPECT_TRUE(stats == PipelineStatistics{});
}

// ---------------------------------------------------------------------------------------------
// Post-transform cache: the vertex shader runs once per unique index, never for vertices the
// indices skip.

TEST(DrawVertexCache, OneInvocationPerUniqueIndex) {
  std::vector<glm::vec4> v;
  for (int i = 0; i < 10; ++i) v.push_back({-0.9f + 0.2f * i, (i % 2) ? 0.8f : -0.8f, 0, 1});
  struct Case {
    std::vector<uint32_t> indices;
    uint64_t unique;
  };
  const Case cases[] = {
      {{0, 1, 2, 2, 1, 3, 3, 1, 4, 0, 2, 5, 5, 2, 3}, 6},
      {{9, 9, 9}, 1},
      {{7, 8, 9, 9, 8, 7, 7, 9, 8}, 3},
      {{0, 1, 2, 3, 4, 5, 6, 7, 8}, 9},
  };
  for (const Case& c : cases) {
    Framebuffer fb(32, 32);
    PipelineStatistics stats;
    const DrawOutcome r = drawCounting(fb, stateWith({0, 0, 32, 32}), v, c.indices, stats);
    ASSERT_TRUE(r.status.isOk()) << r.status.message();
    EXPECT_EQ(r.vertexCalls, c.unique);
    EXPECT_EQ(stats.vertexShaderInvocations, c.unique);
    EXPECT_EQ(stats.inputIndices, c.indices.size());
  }

  // A real mesh: every one of its 1839 vertices is used, each by about 6 triangles.
  Mesh mesh;
  const Status s = loadObj(std::string(RASTER_SHARED_MESHES) + "/bunny_lowres.obj", mesh);
  ASSERT_TRUE(s.isOk()) << s.message();
  std::vector<glm::vec4> positions;
  for (const MeshVertex& mv : mesh.vertices)
    positions.push_back(glm::vec4(mv.position * 0.1f, 1.0f));
  const std::set<uint32_t> unique(mesh.indices.begin(), mesh.indices.end());
  Framebuffer fb(64, 64);
  PipelineStatistics stats;
  const DrawOutcome r = drawCounting(fb, stateWith({0, 0, 64, 64}), positions, mesh.indices, stats);
  ASSERT_TRUE(r.status.isOk());
  EXPECT_EQ(unique.size(), 1839u);
  EXPECT_EQ(r.vertexCalls, unique.size());
  EXPECT_EQ(stats.vertexShaderInvocations, unique.size());
  EXPECT_EQ(stats.inputIndices, mesh.indices.size());
}

// The cache renumbers vertices; the triangles must still get their own vertices: drawing a
// vertex buffer through a scattered index buffer gives the same image as drawing it in order.
// The ordered draw uses every vertex of its buffer, so it takes the vertex stage's path without
// renumbering; the scattered one leaves most of its buffer unused and is renumbered: the two
// paths must agree on every bit and counter.
TEST(DrawVertexCache, ScatteredIndicesGiveSameImage) {
  const uint64_t seed = 0xcac4e;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f);
  std::vector<glm::vec4> ordered;
  for (int i = 0; i < 60; ++i) ordered.push_back({u(rng), u(rng), 0.5f * u(rng), 1.0f});
  // A strip: triangles (i, i+1, i+2), so most vertices are shared by three triangles.
  std::vector<uint32_t> orderedIdx;
  for (uint32_t i = 0; i + 2 < ordered.size(); ++i) orderedIdx.insert(orderedIdx.end(), {i, i + 1, i + 2});
  // Vertex i goes to slot perm[i] of a larger buffer padded with garbage.
  std::vector<uint32_t> perm(200);
  for (uint32_t i = 0; i < perm.size(); ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<glm::vec4> scattered(200, glm::vec4(1e6f, -1e6f, 3, 1));
  for (uint32_t i = 0; i < ordered.size(); ++i) scattered[perm[i]] = ordered[i];
  std::vector<uint32_t> scatteredIdx;
  for (const uint32_t i : orderedIdx) scatteredIdx.push_back(perm[i]);
  Framebuffer a(48, 48, true), b(48, 48, true);
  PipelineStatistics sa, sb;
  const DrawOutcome ra = drawCounting(a, stateWith({0, 0, 48, 48}), ordered, orderedIdx, sa);
  const DrawOutcome rb = drawCounting(b, stateWith({0, 0, 48, 48}), scattered, scatteredIdx, sb);
  ASSERT_TRUE(ra.status.isOk() && rb.status.isOk());
  EXPECT_EQ(ra.vertexCalls, ordered.size());
  EXPECT_EQ(rb.vertexCalls, ordered.size());
  EXPECT_EQ(a.colorPlane(), b.colorPlane());
  EXPECT_EQ(a.depthPlane(), b.depthPlane());
  EXPECT_EQ(a.countPlane(), b.countPlane());
  EXPECT_TRUE(sa == sb);
  EXPECT_GT(sa.fragmentsWritten, 500u) << "the draw must show something to compare";
}

// ---------------------------------------------------------------------------------------------
// Determinism: the same draw twice gives the same bits and the same counters.

TEST(DrawDeterminism, SameSceneTwiceIsIdentical) {
  PipelineState state;
  state.viewport = {0, 0, 160, 90};
  Framebuffer first(160, 90, true), second(160, 90, true);
  PipelineStatistics s1, s2;
  ASSERT_TRUE(renderScene(defaultScene(), first, state, ShadingMode::Lambert, s1).isOk());
  ASSERT_TRUE(renderScene(defaultScene(), second, state, ShadingMode::Lambert, s2).isOk());
  EXPECT_EQ(first.colorPlane(), second.colorPlane());
  EXPECT_EQ(first.depthPlane(), second.depthPlane());
  EXPECT_EQ(first.countPlane(), second.countPlane());
  EXPECT_TRUE(s1 == s2) << s1.toJson() << "\nvs\n" << s2.toJson();
  EXPECT_GT(s1.fragmentsWritten, 5000u);

  // Into a framebuffer that was drawn to before: renderScene clears colour and depth; counts are
  // cleared here. The result must not depend on what was there.
  second.clearCounts();
  PipelineStatistics s3;
  ASSERT_TRUE(renderScene(defaultScene(), second, state, ShadingMode::Lambert, s3).isOk());
  EXPECT_EQ(first.colorPlane(), second.colorPlane());
  EXPECT_EQ(first.depthPlane(), second.depthPlane());
  EXPECT_EQ(first.countPlane(), second.countPlane());
  EXPECT_TRUE(s1 == s3);
}

TEST(DrawDeterminism, OverlappingTrianglesTwiceAreIdentical) {
  const uint64_t seed = 0xde7e;
  std::cout << "[ seed ] " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f), c(0.0f, 1.0f);
  std::vector<ColoredVertex> v;
  for (int i = 0; i < 300; ++i)
    v.push_back({glm::vec3(u(rng), u(rng), 0.6f * u(rng)), glm::vec4(c(rng), c(rng), c(rng), 1)});
  std::vector<uint32_t> idx;
  for (int i = 0; i < 600; ++i) idx.push_back(uint32_t(rng() % v.size()));
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()}) {
    PipelineState state = stateWith({0, 0, 96, 64}, format);
    state.depth.compare = CompareOp::LessEqual;  // ties resolved by submission order
    Framebuffer a(96, 64, true), b(96, 64, true);
    PipelineStatistics sa, sb;
    const VertexColorVertexShader vs;
    const VertexColorShader ps;
    const DrawCall<VertexColorVertexShader, VertexColorShader> call{v, idx, vs, ps};
    ASSERT_TRUE(draw(a, state, call, sa).isOk());
    ASSERT_TRUE(draw(b, state, call, sb).isOk());
    EXPECT_EQ(a.colorPlane(), b.colorPlane()) << format.name();
    EXPECT_EQ(a.depthPlane(), b.depthPlane()) << format.name();
    EXPECT_EQ(a.countPlane(), b.countPlane()) << format.name();
    EXPECT_TRUE(sa == sb) << format.name();
    EXPECT_GT(sa.depthTestsFailed, 1000u) << "overlap is what ordering could change";
  }
}

}  // namespace
}  // namespace rast
