// MSAA (per-sample coverage, depth and colour at Direct3D's standard positions; shading once per
// pixel; resolve) and 2x2 quads (derivatives, helper lanes).
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/draw.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/window_space.h"

namespace rast {
namespace {

constexpr PackedColor kWhite = 0xffffffffu, kBlack = 0xff000000u;

PipelineState windowState(int width, int height, FixedPointFormat format) {
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.positionSpace = PositionSpace::Window;
  state.format = format;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  return state;
}

Status drawWhite(Framebuffer& fb, const PipelineState& state, const std::vector<WindowVertex>& v,
                 PipelineStatistics& stats, int threads = 0) {
  std::vector<uint32_t> indices(v.size());
  for (size_t i = 0; i < v.size(); ++i) indices[i] = uint32_t(i);
  const WindowSpaceVertexShader vs;
  const ConstantColorShader ps{glm::vec4(1)};
  ExecutionOptions exec;
  exec.threads = threads;
  return draw(fb, state, DrawCall<WindowSpaceVertexShader, ConstantColorShader>{v, indices, vs, ps},
              stats, exec);
}

// The exact per-sample reference: the snapped triangle's edge functions (top-left rule) at the
// sample's subpixel position.
bool sampleCovered(const std::array<WindowVertex, 3>& tri, int px, int py, int s,
                   const SamplePattern& pattern, FixedPointFormat f) {
  std::array<SnappedPoint, 3> p;
  for (int i = 0; i < 3; ++i)
    p[i] = {snapToSubpixels(tri[i].position.x, f), snapToSubpixels(tri[i].position.y, f)};
  const int64_t area = (int64_t(p[1].x) - p[0].x) * (int64_t(p[2].y) - p[0].y) -
                       (int64_t(p[2].x) - p[0].x) * (int64_t(p[1].y) - p[0].y);
  if (area == 0) return false;
  if (area < 0) std::swap(p[1], p[2]);
  const int64_t sx = pixelCentreSubpixels(px, f) + pattern.offsetX(s, f);
  const int64_t sy = pixelCentreSubpixels(py, f) + pattern.offsetY(s, f);
  for (int i = 0; i < 3; ++i)
    if (EdgeFunction::through(p[i], p[(i + 1) % 3]).at(sx, sy) < 0) return false;
  return true;
}

std::array<WindowVertex, 3> randomTriangle(std::mt19937_64& rng, int width, int height) {
  std::uniform_real_distribution<float> x(-8.0f, float(width) + 8.0f), y(-8.0f, float(height) + 8.0f);
  std::uniform_int_distribution<int> grid(0, 1);
  std::array<WindowVertex, 3> t;
  for (WindowVertex& v : t) {
    v.position = {x(rng), y(rng), 0.5f};
    // Half the vertices on the 1/16 grid of the sample offsets, where ties with samples happen.
    if (grid(rng)) v.position = glm::round(v.position * 16.0f) / 16.0f;
  }
  return t;
}

class Multisample : public ::testing::TestWithParam<std::tuple<int, int>> {};

// Every sample of every pixel against the exact reference, one random triangle per draw.
TEST_P(Multisample, SampleCoverageEqualsExactReference) {
  const auto [samples, bits] = GetParam();
  const FixedPointFormat f = FixedPointFormat::withFractionBits(bits);
  const SamplePattern pattern = SamplePattern::forCount(samples);
  constexpr int kW = 37, kH = 29;
  std::mt19937_64 rng(uint64_t(samples * 100 + bits));
  for (int trial = 0; trial < 150; ++trial) {
    const std::array<WindowVertex, 3> tri = randomTriangle(rng, kW, kH);
    Framebuffer fb(kW, kH, true, samples);
    fb.clear(glm::vec4(0, 0, 0, 1), 1.0f);
    PipelineStatistics stats;
    ASSERT_TRUE(drawWhite(fb, windowState(kW, kH, f), {tri.begin(), tri.end()}, stats));
    uint64_t coveredSamples = 0, shadedPixels = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        int k = 0;
        for (int s = 0; s < samples; ++s) {
          const bool expected = sampleCovered(tri, x, y, s, pattern, f);
          k += expected;
          ASSERT_EQ(fb.sampleColor(x, y, s), expected ? kWhite : kBlack)
              << "trial " << trial << " pixel (" << x << ", " << y << ") sample " << s;
        }
        coveredSamples += uint64_t(k);
        shadedPixels += k > 0;
        // Resolve: each channel the rounded mean of the samples (alpha is 255 in all).
        const uint32_t grey = (uint32_t(k) * 255u + uint32_t(samples) / 2) / uint32_t(samples);
        ASSERT_EQ(fb.color(x, y), grey | grey << 8 | grey << 16 | 0xff000000u);
        ASSERT_EQ(fb.count(x, y), k > 0 ? 1u : 0u);
      }
    EXPECT_EQ(stats.samplesCovered, coveredSamples);
    // Shading runs once per pixel with any covered sample.
    EXPECT_EQ(stats.pixelShaderInvocations, shadedPixels);
    EXPECT_EQ(stats.fragmentsWritten, shadedPixels);
  }
}

// A grid of triangles covering the framebuffer with margin: every sample of every pixel is
// covered by exactly one triangle (the fill rule holds per sample).
TEST_P(Multisample, GridCoversEverySampleOnce) {
  const auto [samples, bits] = GetParam();
  const FixedPointFormat f = FixedPointFormat::withFractionBits(bits);
  constexpr int kW = 24, kH = 24, kCells = 5;
  std::mt19937_64 rng(uint64_t(7 * samples + bits));
  std::uniform_real_distribution<float> jitter(-1.5f, 1.5f);
  // Vertices of a jittered (kCells+1)^2 lattice spanning [-4, 28], snapped to the 1/16 grid half
  // the time so that edges pass exactly through samples.
  std::array<std::array<glm::vec2, kCells + 1>, kCells + 1> lattice;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      glm::vec2 p(-4.0f + 32.0f * float(i) / kCells, -4.0f + 32.0f * float(j) / kCells);
      if (i > 0 && i < kCells) p.x += jitter(rng);
      if (j > 0 && j < kCells) p.y += jitter(rng);
      if ((i + j) % 2) p = glm::round(p * 16.0f) / 16.0f;
      lattice[j][i] = p;
    }
  std::vector<int> perSample(size_t(kW * kH * samples), 0);
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const glm::vec2 a = lattice[j][i], b = lattice[j][i + 1], c = lattice[j + 1][i + 1],
                      d = lattice[j + 1][i];
      for (const std::array<glm::vec2, 3>& t : {std::array{a, b, c}, std::array{a, c, d}}) {
        Framebuffer fb(kW, kH, false, samples);
        fb.clear(glm::vec4(0, 0, 0, 1), 1.0f);
        PipelineStatistics stats;
        ASSERT_TRUE(drawWhite(fb, windowState(kW, kH, f),
                              {{{t[0], 0.5f}}, {{t[1], 0.5f}}, {{t[2], 0.5f}}}, stats));
        for (int s = 0; s < samples; ++s)
          for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
              perSample[size_t((s * kH + y) * kW + x)] += fb.sampleColor(x, y, s) == kWhite;
      }
    }
  for (size_t i = 0; i < perSample.size(); ++i)
    ASSERT_EQ(perSample[i], 1) << "sample " << i / (kW * kH) << " of pixel ("
                               << i % kW << ", " << i / kW % kH << ")";
}

INSTANTIATE_TEST_SUITE_P(SamplesAndPrecision, Multisample,
                         ::testing::Combine(::testing::Values(1, 4, 8), ::testing::Values(4, 8)));

// Depth per sample: two planes crossing inside a pixel row; each sample keeps the nearer one
// at its own position, so the resolve of an edge pixel mixes both colours.
TEST(MultisampleDepth, EachSampleKeepsItsNearestSurface) {
  constexpr int kW = 16, kH = 8, kSamples = 8;
  const FixedPointFormat f = FixedPointFormat::d24_4();
  Framebuffer fb(kW, kH, false, kSamples);
  fb.clear(glm::vec4(0, 0, 0, 1), 1.0f);
  PipelineState state = windowState(kW, kH, f);
  state.depth.compare = CompareOp::Less;
  state.depth.write = true;
  // Plane A: z rises with x from 0.25 to 0.75 across [0, 16]; plane B: constant 0.5 (red).
  // They cross at x = 8: samples left of x = 8 keep A, right of it keep B.
  const std::vector<WindowVertex> a = {{{-8, -8, 0.0f}}, {{40, -8, 1.5f}}, {{-8, 40, 0.0f}}};
  const std::vector<WindowVertex> b = {{{-8, -8, 0.5f}}, {{40, -8, 0.5f}}, {{-8, 40, 0.5f}}};
  PipelineStatistics stats;
  ASSERT_TRUE(drawWhite(fb, state, a, stats));
  const WindowSpaceVertexShader vs;
  const ConstantColorShader red{glm::vec4(1, 0, 0, 1)};
  const std::vector<uint32_t> idx = {0, 1, 2};
  ASSERT_TRUE(draw(fb, state, DrawCall<WindowSpaceVertexShader, ConstantColorShader>{b, idx, vs, red},
                   stats));
  const SamplePattern pattern = SamplePattern::forCount(kSamples);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int s = 0; s < kSamples; ++s) {
        const float sx = float(x) + 0.5f + pattern.offsetXPixels(s);
        // A's depth at the sample is 0.25 + sx / 32 (from its vertices); B wins where that is
        // above 0.5, i.e. sx > 8. No sample lies exactly on x = 8 (offsets are odd sixteenths).
        const PackedColor expected = sx > 8.0f ? 0xff0000ffu : kWhite;
        ASSERT_EQ(fb.sampleColor(x, y, s), expected) << x << "," << y << " sample " << s;
      }
}

TEST(MultisampleValidation, NeedsFourSubpixelBits) {
  Framebuffer fb(8, 8, false, 4);
  PipelineStatistics stats;
  const Status s = drawWhite(fb, windowState(8, 8, FixedPointFormat::withFractionBits(2)),
                             {{{0, 0, 0.5f}}, {{8, 0, 0.5f}}, {{0, 8, 0.5f}}}, stats);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("4 subpixel bits"), std::string::npos) << s.message();
  EXPECT_THROW(Framebuffer(8, 8, false, 2), std::invalid_argument);
}

// ---- 2x2 quads and derivatives --------------------------------------------------------------

// Records each shaded pixel's derivatives of varying 0 and 1.
struct DerivativeProbe {
  static constexpr int kVaryings = 2;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kDerivatives = true;
  std::vector<std::array<float, 4>>* out;
  int width;
  PixelResult operator()(const Fragment<2>& f) const {
    (*out)[size_t(f.y * width + f.x)] = {f.ddx[0], f.ddy[0], f.ddx[1], f.ddy[1]};
    return {glm::vec4(1)};
  }
};

struct AffineVaryingsVS {
  struct Vertex {
    glm::vec3 position;
  };
  static constexpr int kVaryings = 2;
  // u = x/2 + y/4 + 3, v = -x/8 + 2y: affine in window position, so with w = 1 their exact
  // gradients are (1/2, 1/4) and (-1/8, 2).
  ShadedVertex<2> operator()(const Vertex& v) const {
    const float x = v.position.x, y = v.position.y;
    return {glm::vec4(v.position, 1.0f), {x / 2 + y / 4 + 3, -x / 8 + 2 * y}};
  }
};

TEST(Quads, DerivativesOfLinearVaryingsEqualTheirGradients) {
  constexpr int kW = 40, kH = 30;
  Framebuffer fb(kW, kH, true);
  fb.clear(glm::vec4(0, 0, 0, 1), 1.0f);
  std::vector<std::array<float, 4>> probe(size_t(kW * kH), {-1, -1, -1, -1});
  // Vertices on the 1/16 grid (exact after snapping), so the planes' coefficients are exact.
  const std::vector<AffineVaryingsVS::Vertex> v = {
      {{2.0625f, 3.5f, 0.5f}}, {{37.25f, 6.125f, 0.5f}}, {{11.5f, 27.8125f, 0.5f}}};
  const std::vector<uint32_t> idx = {0, 1, 2};
  const AffineVaryingsVS vs;
  const DerivativeProbe ps{&probe, kW};
  PipelineStatistics stats;
  ASSERT_TRUE(draw(fb, windowState(kW, kH, FixedPointFormat::d24_4()),
                   DrawCall<AffineVaryingsVS, DerivativeProbe>{v, idx, vs, ps}, stats));
  uint64_t shaded = 0;
  for (int i = 0; i < kW * kH; ++i) {
    if (fb.countPlane()[size_t(i)] == 0) {
      EXPECT_EQ(probe[size_t(i)][0], -1.0f) << "an uncovered pixel was shaded";
      continue;
    }
    ++shaded;
    EXPECT_EQ(probe[size_t(i)][0], 0.5f);
    EXPECT_EQ(probe[size_t(i)][1], 0.25f);
    EXPECT_EQ(probe[size_t(i)][2], -0.125f);
    EXPECT_EQ(probe[size_t(i)][3], 2.0f);
  }
  EXPECT_EQ(stats.pixelShaderInvocations, shaded);
  EXPECT_GT(stats.pixelHelperLanes, 0u);
}

// A triangle covering one pixel runs one quad: one shaded lane, three helper lanes, one write.
TEST(Quads, HelperLanesAreCountedAndNeverWrite) {
  constexpr int kW = 8, kH = 8;
  std::vector<std::array<float, 4>> probe(size_t(kW * kH), {-1, -1, -1, -1});
  const AffineVaryingsVS vs;
  const DerivativeProbe ps{&probe, kW};
  const std::vector<uint32_t> idx = {0, 1, 2};
  // Around the centre of pixel (3, 5) only.
  const std::vector<AffineVaryingsVS::Vertex> v = {
      {{3.25f, 5.25f, 0.5f}}, {{3.75f, 5.25f, 0.5f}}, {{3.5f, 5.75f, 0.5f}}};
  Framebuffer fb(kW, kH, true);
  fb.clear(glm::vec4(0, 0, 0, 1), 1.0f);
  PipelineStatistics stats;
  ASSERT_TRUE(draw(fb, windowState(kW, kH, FixedPointFormat::d24_4()),
                   DrawCall<AffineVaryingsVS, DerivativeProbe>{v, idx, vs, ps}, stats));
  EXPECT_EQ(stats.pixelShaderInvocations, 1u);
  EXPECT_EQ(stats.pixelHelperLanes, 3u);
  EXPECT_EQ(stats.fragmentsWritten, 1u);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      EXPECT_EQ(fb.count(x, y), (x == 3 && y == 5) ? 1u : 0u);
      EXPECT_EQ(fb.color(x, y), (x == 3 && y == 5) ? kWhite : kBlack);
    }
  // The derivatives come from helper lanes (the covered pixel is the quad's bottom-right lane).
  EXPECT_EQ(probe[5 * kW + 3][0], 0.5f);
  EXPECT_EQ(probe[5 * kW + 3][3], 2.0f);
}

}  // namespace
}  // namespace rast
