// The back end's shortcuts change no output bit: a shader declared kPerTriangle (run once per
// triangle and tile) and the deferred whole-tile writes it allows (a tile's depth kept as the
// covering triangle's plane until a lane is needed) give the colour, depth and statistics of the
// same shader run per pixel with every lane written at once; and a bin entry flagged
// kWholeTileBit (no coverage test in the back end) is a tile that coverTile finds inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include <glm/vec2.hpp>

#include "pipeline/draw.h"
#include "rasterizer/coverage.h"
#include "shaders_cpp/window_space.h"
#include "tests/window_draw.h"

namespace rast {
namespace {

// The colour depends on the triangle alone, so layers and small triangles are told apart.
glm::vec4 colorOfTriangle(uint32_t primitiveId, bool frontFacing) {
  return {float(primitiveId % 7) / 6.0f, float(primitiveId % 5) / 4.0f, frontFacing ? 1.0f : 0.25f,
          1.0f};
}

// A shader whose colour is `Color` of the triangle alone, declared kPerTriangle (run once per
// triangle and tile) or not (shaded per pixel, every write per lane).
template <glm::vec4 (*Color)(uint32_t primitiveId, bool frontFacing), bool PerTriangle>
struct TriangleColorShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kPerTriangle = PerTriangle;
  PixelResult operator()(const Fragment<0>& f) const {
    return {Color(f.primitiveId, f.frontFacing)};
  }
};
using PerTriangleShader = TriangleColorShader<colorOfTriangle, true>;
using PerPixelShader = TriangleColorShader<colorOfTriangle, false>;
static_assert(kShadesPerTriangle<PerTriangleShader> && !kShadesPerTriangle<PerPixelShader>);

struct Scene {
  int width, height;
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
};

void addQuad(Scene& s, float x0, float y0, float x1, float y1, float z) {
  const uint32_t base = uint32_t(s.vertices.size());
  for (glm::vec2 p : {glm::vec2(x0, y0), glm::vec2(x1, y0), glm::vec2(x1, y1), glm::vec2(x0, y1)})
    s.vertices.push_back({glm::vec3(p, z)});
  for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(base + k);
}

// Full-screen layers at sloped and flat depths, in both orders, with small random triangles
// between them (they read and partly write tiles whose depth is still a deferred plane) and a
// size that leaves partial tiles at the right and bottom edges.
Scene layeredScene(uint32_t seed) {
  Scene s{203, 117, {}, {}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int layer = 0; layer < 12; ++layer) {
    const int order = layer < 6 ? 5 - layer : layer;  // far to near, then near to far
    const float z = 0.1f + 0.07f * float(order);
    if (layer % 3 == 2) {
      // A sloped layer: depth varies across every tile.
      const uint32_t base = uint32_t(s.vertices.size());
      s.vertices.push_back({glm::vec3(-4, -4, z)});
      s.vertices.push_back({glm::vec3(220, -4, z + 0.05f)});
      s.vertices.push_back({glm::vec3(220, 130, z + 0.02f)});
      s.vertices.push_back({glm::vec3(-4, 130, z - 0.03f)});
      for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(base + k);
    } else {
      addQuad(s, 0, 0, float(s.width), float(s.height), z);
    }
    for (int k = 0; k < 6; ++k) {
      const uint32_t base = uint32_t(s.vertices.size());
      const float cx = unit(rng) * float(s.width), cy = unit(rng) * float(s.height);
      for (int v = 0; v < 3; ++v)
        s.vertices.push_back({glm::vec3(cx + 30.0f * (unit(rng) - 0.5f),
                                        cy + 30.0f * (unit(rng) - 0.5f), unit(rng))});
      for (uint32_t v : {0u, 1u, 2u}) s.indices.push_back(base + v);
    }
  }
  return s;
}

constexpr glm::vec4 kClearColor(0.5f, 0.5f, 0.5f, 1.0f);

using Result = testing_support::DrawnFrame;  // counts unused
using testing_support::sameFrame;

template <class PS>
Result render(const Scene& scene, const PipelineState& state, int samples, float clearDepth,
              BackEndTarget target = BackEndTarget::Auto) {
  Framebuffer fb(scene.width, scene.height, false, samples);
  fb.clear(kClearColor, clearDepth);
  const WindowSpaceVertexShader vs;
  const PS ps;
  Result r;
  ExecutionOptions exec;
  exec.backEnd = target;
  // Two draws: the second starts on tiles the first left as planes, stored and loaded again.
  for (int pass = 0; pass < 2; ++pass)
    EXPECT_TRUE(draw(fb, state, DrawCall<WindowSpaceVertexShader, PS>{scene.vertices, scene.indices,
                                                                      vs, ps},
                     r.stats, exec));
  r.color = fb.colorPlane();
  r.depth = fb.depthPlane();
  return r;
}


TEST(TileShortcuts, PerTriangleShadingAndDeferredWritesChangeNoBit) {
  const Scene scene = layeredScene(7);
  int cases = 0;
  for (int samples : {1, 4, 8})
    for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24, DepthFormat::Unorm16})
      for (CompareOp compare : {CompareOp::Less, CompareOp::LessEqual, CompareOp::Greater,
                                CompareOp::Always, CompareOp::Equal})
        for (bool depthWrite : {true, false})
          for (bool colorWrite : {true, false}) {
            PipelineState state;
            state.viewport = {0, 0, scene.width, scene.height};
            state.positionSpace = PositionSpace::Window;
            state.depth.compare = compare;
            state.depth.write = depthWrite;
            state.depth.format = format;
            state.colorWrite = colorWrite;
            const float clearDepth = compare == CompareOp::Greater ? 0.0f : 1.0f;
            SCOPED_TRACE(testing::Message() << samples << " samples, format " << int(format)
                                            << ", compare " << int(compare) << ", depth write "
                                            << depthWrite << ", colour write " << colorWrite);
            const Result perPixel = render<PerPixelShader>(scene, state, samples, clearDepth);
            ASSERT_TRUE(sameFrame(render<PerTriangleShader>(scene, state, samples, clearDepth),
                                   perPixel));
            // The x86-64 baseline build of the tile loop against the best one (AVX2 here).
            ASSERT_TRUE(sameFrame(render<PerPixelShader>(scene, state, samples, clearDepth,
                                                          BackEndTarget::Baseline),
                                   perPixel));
            ++cases;
          }
  EXPECT_EQ(cases, 3 * 3 * 5 * 2 * 2);
}

// Colours that differ from triangle to triangle in any one channel alone: each channel is 0.25 or
// 1 by its own bit of a hash of the primitive id. The tile loop packs a per-triangle colour only
// when it differs from the last one packed, and every channel must count in that comparison.
glm::vec4 colorByHash(uint32_t primitiveId, bool /*frontFacing*/) {
  const uint32_t h = primitiveId * 2654435761u >> 16;
  auto channel = [&](int k) { return (h >> k & 1) ? 1.0f : 0.25f; };
  return {channel(0), channel(1), channel(2), channel(3)};
}
using HashColorPerTriangle = TriangleColorShader<colorByHash, true>;
using HashColorPerPixel = TriangleColorShader<colorByHash, false>;

// Many small triangles over few tiles, no depth test: every tile takes dozens of triangles in a
// row, and each pixel keeps the colour of the last triangle that covers it.
TEST(TileShortcuts, PerTriangleColoursDifferingInOneChannelAreEachWritten) {
  Scene scene{45, 37, {}, {}};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int k = 0; k < 3000; ++k) {
    const uint32_t base = uint32_t(scene.vertices.size());
    const float cx = unit(rng) * 45.0f, cy = unit(rng) * 37.0f;
    for (int v = 0; v < 3; ++v)
      scene.vertices.push_back(
          {glm::vec3(cx + 6.0f * (unit(rng) - 0.5f), cy + 6.0f * (unit(rng) - 0.5f), 0.5f)});
    for (uint32_t v : {0u, 1u, 2u}) scene.indices.push_back(base + v);
  }
  PipelineState state;
  state.viewport = {0, 0, scene.width, scene.height};
  state.positionSpace = PositionSpace::Window;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  const Result perPixel = render<HashColorPerPixel>(scene, state, 1, 1.0f);
  EXPECT_TRUE(sameFrame(render<HashColorPerTriangle>(scene, state, 1, 1.0f), perPixel));
  // All sixteen colours are left on screen (besides the clear colour, where no triangle
  // reached), so no channel is constant.
  std::vector<PackedColor> colors = perPixel.color;
  std::erase(colors, packColor(kClearColor));
  std::sort(colors.begin(), colors.end());
  colors.erase(std::unique(colors.begin(), colors.end()), colors.end());
  EXPECT_EQ(colors.size(), 16u);
}

// The scene exercises what it should: layers cover whole tiles (the deferred case) and later
// triangles read them back.
TEST(TileShortcuts, SceneHasWholeTileOverwritesAndPartialReads) {
  const Scene scene = layeredScene(7);
  PipelineState state;
  state.viewport = {0, 0, scene.width, scene.height};
  state.positionSpace = PositionSpace::Window;
  const Result r = render<PerTriangleShader>(scene, state, 1, 1.0f);
  EXPECT_GT(r.stats.tilesTriviallyAccepted, 12u * (203 / 8) * (117 / 8));
  EXPECT_GT(r.stats.tilesPartial, 100u);
  EXPECT_GT(r.stats.depthTestsFailed, 0u);
  EXPECT_GT(r.stats.depthTestsPassed, 0u);
}

// Every flagged entry is a tile whose every sample coverTile finds inside; with one sample, every
// tile of a multi-tile triangle that coverTile finds inside is flagged (so the shortcut is taken
// wherever it could be). Large random triangles, both precisions, 1, 4 and 8 samples.
TEST(TileShortcuts, WholeTileBinEntriesAreTilesCoverTileFindsInside) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-100.0, 740.0), y(-100.0, 460.0);
  const PixelRect screen{0, 0, 640, 360};
  CoverageKernel scalar;
  ASSERT_TRUE(findCoverageKernel("scalar", scalar));
  uint64_t flagged = 0;
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()})
    for (const int samples : {1, 4, 8}) {
      const SamplePattern pattern = SamplePattern::forCount(samples);
      const int32_t reach = pattern.reach(format);
      std::vector<std::vector<SetupTriangle<0>>> chunks(1);
      for (int i = 0; i < 400; ++i) {
        std::array<SnappedPoint, 3> v;
        for (SnappedPoint& p : v)
          p = {snapToSubpixels(x(rng), format), snapToSubpixels(y(rng), format)};
        CoverageSetup c;
        if (setupCoverage(v, screen, format, c, FillRule::TopLeft, reach) != SetupOutcome::Accepted)
          continue;
        SetupTriangle<0> t;
        t.edges = c.edges;
        t.bounds = TriangleBounds(c.bounds);
        chunks[0].push_back(t);
      }
      TileBins bins(screen.x1, screen.y1);
      PipelineStatistics stats;
      bins.build(chunks, format, reach, &SetupTriangles<0>::id, stats);
      std::vector<uint32_t> scratch;
      for (int tile = 0; tile < bins.tileCount(); ++tile)
        for (const uint32_t entry : bins.entries(tile, scratch)) {
          const SetupTriangle<0>& t = chunks[0][entry & ~kWholeTileBit];
          const int tx = tile % bins.tilesX(), ty = tile / bins.tilesX();
          bool allInside = true;
          for (int s = 0; s < samples; ++s) {
            const TileCoverageResult r =
                coverTile(scalar, t.edges, t.bounds, tx, ty, format, pattern.offsetX(s, format),
                          pattern.offsetY(s, format));
            allInside &= r.kind == TileCoverage::Inside && r.mask == kFullMask;
          }
          if (entry & kWholeTileBit) {
            ++flagged;
            ASSERT_TRUE(allInside) << "tile " << tile << ", " << samples << " samples";
          } else if (samples == 1 && allInside) {
            const bool oneTile = (t.bounds.x0 >> kTileShift) == ((t.bounds.x1 - 1) >> kTileShift) &&
                                 (t.bounds.y0 >> kTileShift) == ((t.bounds.y1 - 1) >> kTileShift);
            EXPECT_TRUE(oneTile) << "tile " << tile << " is inside but not flagged";
          }
        }
    }
  EXPECT_GT(flagged, 10000u);
}

}  // namespace
}  // namespace rast
