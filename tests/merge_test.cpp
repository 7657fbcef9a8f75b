// The output merger: depth compare, depth and colour write masks, early depth, discard, and the
// identities between the pipeline's counters.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <string>
#include <vector>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

constexpr int kSize = 16;
constexpr uint32_t kPixels = kSize * kSize;

const glm::vec4 kClearColor(1, 0, 0, 1);
const glm::vec4 kDrawColor(0, 1, 0, 1);

// Two triangles exactly covering the framebuffer: every pixel centre once. Depth z0 on the left
// edge, z1 on the right, linear in x: pixel column i gets z0 + (z1 - z0) * (i + 0.5) / 16, exact in
// float for the values used here.
std::vector<WindowVertex> screenQuad(float z0, float z1) {
  const float s = kSize;
  return {
      {glm::vec3(0, 0, z0)}, {glm::vec3(s, 0, z1)}, {glm::vec3(s, s, z1)}, {glm::vec3(0, s, z0)}};
}
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

PipelineState windowState(CompareOp op, bool depthWrite) {
  PipelineState s;
  s.viewport = {0, 0, kSize, kSize};
  s.positionSpace = PositionSpace::Window;
  s.depth.compare = op;
  s.depth.write = depthWrite;
  return s;
}

// Colour from the fragment's position and depth, so that images show which fragment won where;
// counts its own invocations; discards on odd x + y when asked to.
template <bool Discard>
struct ProbeShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = Discard;
  static constexpr bool kSideEffects = true;  // runs once per passing fragment
  std::atomic<uint64_t>* invocations;

  PixelResult operator()(const Fragment<0>& f) const {
    invocations->fetch_add(1, std::memory_order_relaxed);
    if (Discard && (f.x + f.y) % 2 == 1) return PixelResult::discarded();
    return {glm::vec4(f.x / 16.0f, f.y / 16.0f, f.depth, 1.0f)};
  }
};

struct Image {
  std::vector<PackedColor> color;
  std::vector<float> depth;
  std::vector<uint32_t> counts;
  friend bool operator==(const Image&, const Image&) = default;
};

Image imageOf(const Framebuffer& fb) { return {fb.colorPlane(), fb.depthPlane(), fb.countPlane()}; }

template <class PS>
PipelineStatistics drawQuad(Framebuffer& fb, const PipelineState& state,
                            const std::vector<WindowVertex>& quad, const PS& ps) {
  PipelineStatistics stats;
  const WindowSpaceVertexShader vs;
  const Status s =
      draw(fb, state, DrawCall<WindowSpaceVertexShader, PS>{quad, kQuadIndices, vs, ps}, stats);
  EXPECT_TRUE(s.isOk()) << s.message();
  return stats;
}

const char* opName(CompareOp op) {
  constexpr const char* names[] = {"Never",   "Less",     "Equal",        "LessEqual",
                                   "Greater", "NotEqual", "GreaterEqual", "Always"};
  return names[int(op)];
}

// ---------------------------------------------------------------------------------------------

struct TruthRow {
  CompareOp op;
  bool less, equal, greater;  // passes for fragment depth <, ==, > the stored depth
};
constexpr TruthRow kTruthTable[] = {
    {CompareOp::Never, false, false, false},      {CompareOp::Less, true, false, false},
    {CompareOp::Equal, false, true, false},       {CompareOp::LessEqual, true, true, false},
    {CompareOp::Greater, false, false, true},     {CompareOp::NotEqual, true, false, true},
    {CompareOp::GreaterEqual, false, true, true}, {CompareOp::Always, true, true, true},
};

// A fragment at depth d over a stored depth s = 0.5, for d < s, d == s, d > s; with depth writes
// on and off, early depth on and off.
TEST(MergeDepth, CompareTruthTable) {
  const float stored = 0.5f;
  for (const TruthRow& row : kTruthTable) {
    for (const float d : {0.25f, 0.5f, 0.75f}) {
      const bool pass = d < stored ? row.less : d == stored ? row.equal : row.greater;
      for (const bool write : {true, false}) {
        for (const bool early : {true, false}) {
          const std::string what = std::string(opName(row.op)) + " d=" + std::to_string(d) +
                                   (write ? " write" : " no-write") + (early ? " early" : " late");
          Framebuffer fb(kSize, kSize, true);
          fb.clear(kClearColor, stored);
          PipelineState state = windowState(row.op, write);
          state.depth.early = early;
          const ConstantColorShader ps{kDrawColor};
          const PipelineStatistics s = drawQuad(fb, state, screenQuad(d, d), ps);

          for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
              ASSERT_EQ(fb.count(x, y), pass ? 1u : 0u) << what;
              ASSERT_EQ(fb.color(x, y), packColor(pass ? kDrawColor : kClearColor)) << what;
              ASSERT_EQ(fb.depth(x, y), pass && write ? d : stored) << what;
            }
          EXPECT_EQ(s.samplesCovered, kPixels) << what;
          EXPECT_EQ(s.fragmentsWritten, pass ? kPixels : 0u) << what;
          // Always makes no comparison (nothing is read): neither counter moves. Every other
          // function, Never included, counts each covered sample as passed or failed.
          const bool compared = row.op != CompareOp::Always;
          EXPECT_EQ(s.depthTestsPassed, compared && pass ? kPixels : 0u) << what;
          EXPECT_EQ(s.depthTestsFailed, compared && !pass ? kPixels : 0u) << what;
          // Early depth shades only what passed; late depth shades everything covered.
          EXPECT_EQ(s.pixelShaderInvocations, early && !pass ? 0u : kPixels) << what;
        }
      }
    }
  }
}

bool passesAt(CompareOp op, float fragment, float stored) {
  switch (op) {
    case CompareOp::Never: return depthPasses<CompareOp::Never>(fragment, stored);
    case CompareOp::Less: return depthPasses<CompareOp::Less>(fragment, stored);
    case CompareOp::Equal: return depthPasses<CompareOp::Equal>(fragment, stored);
    case CompareOp::LessEqual: return depthPasses<CompareOp::LessEqual>(fragment, stored);
    case CompareOp::Greater: return depthPasses<CompareOp::Greater>(fragment, stored);
    case CompareOp::NotEqual: return depthPasses<CompareOp::NotEqual>(fragment, stored);
    case CompareOp::GreaterEqual: return depthPasses<CompareOp::GreaterEqual>(fragment, stored);
    case CompareOp::Always: return depthPasses<CompareOp::Always>(fragment, stored);
  }
  return false;
}

// The tile loop's 64-lane depth test (SIMD compares turned into mask bits) against depthPasses,
// lane by lane: every compare op, every pair of values that includes NaN, both zeros, infinities
// and a denormal, under a mask, on every range of rows. Lanes outside the rows or the mask must
// come out clear (except for Always, which tests nothing).
TEST(MergeDepth, TileDepthTestAgreesWithDepthPassesOnEveryLane) {
  const float kNaN = std::numeric_limits<float>::quiet_NaN();
  const float kInf = std::numeric_limits<float>::infinity();
  const std::array<float, 9> values = {kNaN, -kInf, -1.0f, -0.0f, 0.0f, 1e-40f, 0.5f, 1.0f, kInf};
  constexpr int kPairs = int(values.size() * values.size());  // 81: two tiles' worth of lanes
  uint64_t pattern = 0x9e3779b97f4a7c15ull;
  int checkedPasses = 0, checkedFails = 0;
  for (const TruthRow& row : kTruthTable) {
    for (int first = 0; first < kPairs; first += kTileLanes) {
      TileLanes<float> z{}, stored{};
      for (int lane = 0; lane < kTileLanes; ++lane) {
        const int pair = (first + lane) % kPairs;
        z[lane] = values[size_t(pair) % values.size()];
        stored[lane] = values[size_t(pair) / values.size()];
      }
      for (int rowBegin = 0; rowBegin < kTileSize; ++rowBegin)
        for (int rowEnd = rowBegin + 1; rowEnd <= kTileSize; ++rowEnd) {
          pattern = pattern * 6364136223846793005ull + 1442695040888963407ull;
          for (const CoverageMask mask : {kFullMask, pattern}) {
            const CoverageMask got = depthTestInline(row.op, z, stored, mask, rowBegin, rowEnd);
            for (int lane = 0; lane < kTileLanes; ++lane) {
              const bool inRows = lane / kTileSize >= rowBegin && lane / kTileSize < rowEnd;
              // Always tests nothing: the mask comes back whole.
              const bool want = row.op == CompareOp::Always
                                    ? (mask >> lane & 1) != 0
                                    : inRows && (mask >> lane & 1) &&
                                          passesAt(row.op, z[lane], stored[lane]);
              ASSERT_EQ((got >> lane & 1) != 0, want)
                  << opName(row.op) << " fragment " << z[lane] << " stored " << stored[lane]
                  << " lane " << lane << " rows [" << rowBegin << ", " << rowEnd << ")";
              if (inRows && (mask >> lane & 1)) ++(want ? checkedPasses : checkedFails);
            }
          }
        }
    }
  }
  EXPECT_GT(checkedPasses, 10000);
  EXPECT_GT(checkedFails, 10000);
}

// Colour writes off: the colour plane is untouched while depth and counts still follow the test.
// A shader that cannot discard then has no visible effect and is not run (tile_loop.h).
TEST(MergeColorWrite, OffLeavesColourUnchanged) {
  for (const TruthRow& row : kTruthTable) {
    Framebuffer fb(kSize, kSize, true);
    fb.clear(kClearColor, 0.5f);
    const std::vector<PackedColor> before = fb.colorPlane();
    PipelineState state = windowState(row.op, true);
    state.colorWrite = false;
    // Column i at depth (i + 0.5) / 16: "less" on the left half, "greater" on the right.
    const PipelineStatistics s =
        drawQuad(fb, state, screenQuad(0.0f, 1.0f), ConstantColorShader{kDrawColor});
    EXPECT_EQ(fb.colorPlane(), before) << opName(row.op);
    EXPECT_EQ(s.pixelShaderInvocations, 0u) << opName(row.op);
    uint32_t written = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float z = (x + 0.5f) / kSize;
        const bool pass = z < 0.5f ? row.less : z == 0.5f ? row.equal : row.greater;
        EXPECT_EQ(fb.count(x, y), pass ? 1u : 0u) << opName(row.op) << " " << x << "," << y;
        EXPECT_EQ(fb.depth(x, y), pass ? z : 0.5f) << opName(row.op) << " " << x << "," << y;
        written += pass;
      }
    EXPECT_EQ(s.fragmentsWritten, written) << opName(row.op);
  }
}

// ---------------------------------------------------------------------------------------------
// Early depth: a quad at depth 0.5 first, then one whose depth runs from 0 (left) to 1 (right):
// exactly the 8 left columns of the second pass the Less test. Early depth shades only those; late
// depth shades all, and the images are identical.
TEST(MergeEarlyDepth, SkipsShadingOfHiddenFragmentsWithIdenticalImage) {
  Image images[2];
  for (const bool early : {true, false}) {
    Framebuffer fb(kSize, kSize, true);
    fb.clear(kClearColor, 1.0f);
    PipelineState state = windowState(CompareOp::Less, true);
    state.depth.early = early;
    std::atomic<uint64_t> calls{0};
    const ProbeShader<false> ps{&calls};
    drawQuad(fb, state, screenQuad(0.5f, 0.5f), ps);
    calls = 0;
    const PipelineStatistics s = drawQuad(fb, state, screenQuad(0.0f, 1.0f), ps);
    const std::string what = early ? "early" : "late";
    EXPECT_EQ(s.samplesCovered, kPixels) << what;
    EXPECT_EQ(s.depthTestsPassed, 8u * kSize) << what;
    EXPECT_EQ(s.depthTestsFailed, 8u * kSize) << what;
    EXPECT_EQ(s.fragmentsWritten, 8u * kSize) << what;
    EXPECT_EQ(s.pixelShaderInvocations, early ? 8u * kSize : kPixels) << what;
    EXPECT_EQ(calls.load(), s.pixelShaderInvocations) << what << ": the shader's own count";
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) EXPECT_EQ(fb.count(x, y), x < 8 ? 2u : 1u) << what;
    images[early ? 0 : 1] = imageOf(fb);
  }
  EXPECT_TRUE(images[0] == images[1]) << "early and late depth must give the same image";
}

// A discarding shader writes nothing (colour, depth, count) for the fragments it discards, with
// early and late depth, with colour writes on and off.
TEST(MergeDiscard, DiscardedFragmentsWriteNothing) {
  Image reference;
  for (const bool early : {true, false}) {
    for (const bool colorWrite : {true, false}) {
      Framebuffer fb(kSize, kSize, true);
      fb.clear(kClearColor, 0.5f);
      PipelineState state = windowState(CompareOp::Less, true);
      state.depth.early = early;
      state.colorWrite = colorWrite;
      std::atomic<uint64_t> calls{0};
      const PipelineStatistics s =
          drawQuad(fb, state, screenQuad(0.25f, 0.25f), ProbeShader<true>{&calls});
      const std::string what =
          std::string(early ? "early" : "late") + (colorWrite ? "" : " no-colour");
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const bool kept = (x + y) % 2 == 0;
          EXPECT_EQ(fb.count(x, y), kept ? 1u : 0u) << what;
          EXPECT_EQ(fb.depth(x, y), kept ? 0.25f : 0.5f) << what;
          const PackedColor expected = kept && colorWrite
                                           ? packColor(glm::vec4(x / 16.0f, y / 16.0f, 0.25f, 1))
                                           : packColor(kClearColor);
          EXPECT_EQ(fb.color(x, y), expected) << what << " " << x << "," << y;
        }
      EXPECT_EQ(s.pixelShaderInvocations, kPixels) << what;
      EXPECT_EQ(calls.load(), kPixels) << what;
      EXPECT_EQ(s.fragmentsDiscarded, kPixels / 2) << what;
      EXPECT_EQ(s.fragmentsWritten, kPixels / 2) << what;
      // Early: every fragment is tested before the shader discards half. Late: only survivors.
      EXPECT_EQ(s.depthTestsPassed, early ? kPixels : kPixels / 2) << what;
      EXPECT_EQ(s.depthTestsFailed, 0u) << what;
      if (colorWrite) {
        if (early)
          reference = imageOf(fb);
        else
          EXPECT_TRUE(imageOf(fb) == reference) << "early and late depth differ with discard";
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Statistics identities over a draw holding one triangle of every fate.

ShadedVertex<0> windowToClip(double wx, double wy, double zNdc, double w = 1.0) {
  // 32x32 viewport: NDC = window / 16 - 1, y flipped.
  return {glm::vec4(float((wx / 16 - 1) * w), float((1 - wy / 16) * w), float(zNdc * w), float(w)),
          {}};
}

struct PositionVS {
  using Vertex = ShadedVertex<0>;
  static constexpr int kVaryings = 0;
  ShadedVertex<0> operator()(const Vertex& v) const { return v; }
};

TEST(MergeStatistics, IdentitiesHoldForEveryTriangleFate) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // Front faces run counter-clockwise on screen (the default), so the visible ones do.
  const std::vector<ShadedVertex<0>> v = {
      {glm::vec4(nan, 0, 0, 1)},
      windowToClip(5, 5, 0),
      windowToClip(9, 5, 0),  // 0..2: NaN
      {glm::vec4(0, 0, 0, inf)},
      windowToClip(5, 9, 0),
      windowToClip(9, 9, 0),  // 3..5: Inf
      windowToClip(-10, 5, 0),
      windowToClip(-5, 20, 0),
      windowToClip(-20, 10, 0),  // left of view
      windowToClip(2, 2, 2),
      windowToClip(2, 30, 2),
      windowToClip(30, 16, 2),  // beyond far
      windowToClip(2, 2, 0),
      windowToClip(2, 30, 0),
      windowToClip(30, 16, 0),  // visible
      windowToClip(4, 4, 0),
      windowToClip(8, 8, 0),
      windowToClip(12, 12, 0),  // zero area
      windowToClip(20, 4, 0),
      windowToClip(28, 4, 0),
      windowToClip(20, 12, 0),  // back face
      windowToClip(3.1, 3.1, 0),
      windowToClip(3.1, 3.4, 0),
      windowToClip(3.4, 3.1, 0),  // no sample
      // One vertex nearer than the near plane: two triangles after clipping, partly behind the
      // visible triangle (depth 0.75 against 0.5), partly in front (towards the near plane).
      windowToClip(6, 6, -3),
      windowToClip(16, 28, 0.5),
      windowToClip(26, 8, 0.5)};
  std::vector<uint32_t> indices(v.size());
  for (uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;

  PipelineState state;
  state.viewport = {0, 0, 32, 32};
  state.cullMode = CullMode::Back;
  Framebuffer fb(32, 32, true);
  PipelineStatistics s;
  const PositionVS vs;
  std::atomic<uint64_t> calls{0};
  const ProbeShader<false> ps{&calls};
  ASSERT_TRUE(
      draw(fb, state, DrawCall<PositionVS, ProbeShader<false>>{v, indices, vs, ps}, s).isOk());

  EXPECT_EQ(s.inputTriangles, 9u);
  EXPECT_EQ(s.clipNonFinite, 2u);
  EXPECT_EQ(s.clipTrivialReject, 2u);
  EXPECT_EQ(s.clipClipped, 1u);
  EXPECT_EQ(s.clipOutputTriangles, 6u);  // 4 unclipped + 2 from the clipped one
  EXPECT_EQ(s.clipDegenerate, 0u);
  EXPECT_EQ(s.setupZeroArea, 1u);
  EXPECT_EQ(s.setupCulledBack, 1u);
  EXPECT_EQ(s.setupCulledFront, 0u);
  EXPECT_EQ(s.setupNoSamples, 1u);
  EXPECT_EQ(s.setupTriangles, 3u);

  // Every input triangle has exactly one fate in the clipper ...
  const uint64_t fromClipped = 2;
  EXPECT_EQ(s.inputTriangles, s.clipNonFinite + s.clipTrivialReject + s.clipClipped +
                                  (s.clipOutputTriangles - fromClipped));
  // ... and every triangle leaving it exactly one in setup.
  EXPECT_EQ(s.clipOutputTriangles, s.clipDegenerate + s.setupZeroArea + s.setupCulledBack +
                                       s.setupCulledFront + s.setupNoSamples + s.setupTriangles);
  // The depth test is on: every covered sample passes or fails it.
  EXPECT_EQ(s.samplesCovered, s.depthTestsPassed + s.depthTestsFailed);
  EXPECT_GT(s.depthTestsFailed, 0u) << "the draw must exercise both outcomes";
  EXPECT_GT(s.depthTestsPassed, s.depthTestsFailed);
  // Early depth, no discard: exactly the passing fragments are shaded and written.
  EXPECT_EQ(s.pixelShaderInvocations, s.depthTestsPassed);
  EXPECT_EQ(calls.load(), s.pixelShaderInvocations);
  EXPECT_EQ(s.fragmentsDiscarded, 0u);
  EXPECT_EQ(s.fragmentsWritten, s.depthTestsPassed);
  uint64_t countSum = 0;
  for (uint32_t c : fb.countPlane()) countSum += c;
  EXPECT_EQ(s.fragmentsWritten, countSum);
}

}  // namespace
}  // namespace rast
