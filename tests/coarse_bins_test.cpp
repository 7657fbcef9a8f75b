// Two-level binning (bin.h) gives every tile exactly the entries of one-level binning, flags and
// order included, and counts the same rejected tiles; so whole draws give the same colour, depth,
// counts and statistics either way.
#include <gtest/gtest.h>

#include <random>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "pipeline/bin.h"
#include "pipeline/setup.h"
#include "rasterizer/sample_pattern.h"
#include "rasterizer/triangle_setup.h"
#include "window_draw.h"

namespace rast {
namespace {

struct Binned {
  std::vector<std::vector<uint32_t>> entries;  // per tile
  PipelineStatistics stats;
  size_t entryCount = 0, coarseEntries = 0;
};

// Bins `chunks` by build(), or, with `byChunk`, as the front end does: chunk by chunk in
// parallel (startChunks, binChunk, finishChunks), here in reverse order.
Binned binWith(BinLevels levels, int threads, int width, int height,
               const std::vector<std::vector<SetupTriangle<0>>>& chunks, FixedPointFormat format,
               int32_t reach, bool byChunk = false) {
  Binned b;
  TileBins bins(width, height, nullptr, levels);
  tbb::task_arena(threads).execute([&] {
    if (!byChunk) {
      bins.build(chunks, format, reach, &SetupTriangles<0>::id, b.stats);
      return;
    }
    bins.startChunks(chunks.size());
    tbb::parallel_for(size_t{0}, chunks.size(), [&](size_t k) {
      const size_t c = chunks.size() - 1 - k;
      bins.binChunk(c, chunks[c], format, reach, &SetupTriangles<0>::id);
    });
    bins.finishChunks(b.stats);
  });
  std::vector<uint32_t> scratch;
  for (int t = 0; t < bins.tileCount(); ++t) {
    const std::span<const uint32_t> e = bins.entries(t, scratch);
    b.entries.emplace_back(e.begin(), e.end());
  }
  b.entryCount = bins.entryCount();
  b.coarseEntries = bins.coarseEntryCount();
  return b;
}

// Random triangles from a few pixels to several times the screen (so clipped to it), in chunks
// of the given sizes before clipping and culling, with full-screen quads among them.
std::vector<std::vector<SetupTriangle<0>>> randomChunks(const PixelRect& screen,
                                                        FixedPointFormat format, int32_t reach,
                                                        std::mt19937& rng,
                                                        const std::vector<int>& sizes) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<SetupTriangle<0>>> chunks(sizes.size());
  for (size_t c = 0; c < chunks.size(); ++c)
    for (int i = 0; i < sizes[c]; ++i) {
      std::array<SnappedPoint, 3> v;
      if (i % 10 == 0) {
        // Half of a quad over the whole screen, either diagonal.
        const double w = screen.x1, h = screen.y1;
        const bool first = i % 20 == 0;
        const double px[3] = {0, w, first ? w : 0}, py[3] = {0, first ? 0 : h, h};
        for (int k = 0; k < 3; ++k)
          v[k] = {snapToSubpixels(px[k], format), snapToSubpixels(py[k], format)};
      } else {
        const double size = std::pow(2.0, 2.0 + 9.0 * unit(rng));
        const double cx = -200.0 + 1400.0 * unit(rng), cy = -200.0 + 1000.0 * unit(rng);
        for (SnappedPoint& p : v)
          p = {snapToSubpixels(cx + size * (unit(rng) - 0.5), format),
               snapToSubpixels(cy + size * (unit(rng) - 0.5), format)};
      }
      CoverageSetup setup;
      if (setupCoverage(v, screen, format, setup, FillRule::TopLeft, reach) !=
          SetupOutcome::Accepted)
        continue;
      SetupTriangle<0> t;
      t.edges = setup.edges;
      t.bounds = TriangleBounds(setup.bounds);
      chunks[c].push_back(t);
    }
  return chunks;
}

// Random chunks of 60 to 220 triangles; an odd screen size leaves partial tiles and partial
// coarse tiles at the right and bottom.
TEST(CoarseBins, EveryTileGetsTheEntriesOfOneLevelBinning) {
  const PixelRect screen{0, 0, 1001, 587};
  std::mt19937 rng(5);
  size_t coarseTotal = 0;
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()})
    for (const int samples : {1, 4, 8}) {
      const int32_t reach = SamplePattern::forCount(samples).reach(format);
      const std::vector<std::vector<SetupTriangle<0>>> chunks =
          randomChunks(screen, format, reach, rng, {60, 100, 140, 180, 220});
      const Binned one =
          binWith(BinLevels::TilesOnly, 1, screen.x1, screen.y1, chunks, format, reach);
      EXPECT_EQ(one.coarseEntries, 0u);
      for (const int threads : {1, 2, 4}) {
        SCOPED_TRACE(testing::Message() << format.name() << ", " << samples << " samples, "
                                        << threads << " threads");
        const Binned two = binWith(BinLevels::Coarse, threads, screen.x1, screen.y1, chunks, format,
                                   reach);
        ASSERT_EQ(two.entries.size(), one.entries.size());
        for (size_t t = 0; t < one.entries.size(); ++t)
          ASSERT_EQ(two.entries[t], one.entries[t]) << "tile " << t;
        EXPECT_EQ(two.entryCount, one.entryCount);
        EXPECT_EQ(two.stats, one.stats);
        coarseTotal += two.coarseEntries;
      }
    }
  // The coarse level was used, and widely: each full-screen half covers about 60 coarse tiles.
  EXPECT_GT(coarseTotal, 6u * 3u * 2u * 50u * 40u);
}

// The front end's binning, chunk by chunk in the tasks that set the chunks up, gives every tile
// the entries build() gives it, flags and order included, and the same counts, whatever the
// levels and threads: 37 chunks (some empty) make groups of several chunks, which the sort must
// count in submission order.
TEST(CoarseBins, BinningChunkByChunkGivesTheSameBins) {
  const PixelRect screen{0, 0, 773, 451};
  std::mt19937 rng(11);
  std::vector<int> sizes;
  for (int c = 0; c < 37; ++c) sizes.push_back(c % 9 == 4 ? 0 : 8 + 3 * c);
  size_t entries = 0, coarse = 0;
  for (const FixedPointFormat format : {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()})
    for (const int samples : {1, 4}) {
      const int32_t reach = SamplePattern::forCount(samples).reach(format);
      const std::vector<std::vector<SetupTriangle<0>>> chunks =
          randomChunks(screen, format, reach, rng, sizes);
      for (const BinLevels levels : {BinLevels::Coarse, BinLevels::TilesOnly}) {
        const Binned whole = binWith(levels, 1, screen.x1, screen.y1, chunks, format, reach);
        for (const int threads : {1, 2, 4}) {
          SCOPED_TRACE(testing::Message() << format.name() << ", " << samples << " samples, "
                                          << threads << " threads, levels "
                                          << int(levels == BinLevels::Coarse));
          const Binned byChunk =
              binWith(levels, threads, screen.x1, screen.y1, chunks, format, reach, true);
          ASSERT_EQ(byChunk.entries.size(), whole.entries.size());
          for (size_t t = 0; t < whole.entries.size(); ++t)
            ASSERT_EQ(byChunk.entries[t], whole.entries[t]) << "tile " << t;
          EXPECT_EQ(byChunk.entryCount, whole.entryCount);
          EXPECT_EQ(byChunk.coarseEntries, whole.coarseEntries);
          EXPECT_EQ(byChunk.stats, whole.stats);
        }
        entries += whole.entryCount;
        coarse += whole.coarseEntries;
      }
    }
  // Not a vacuous comparison: many entries, and coarse ones among them.
  EXPECT_GT(entries, 100000u);
  EXPECT_GT(coarse, 100u);
}

// Full-screen layers in both orders with small triangles between them, counted: colour, depth,
// counts and statistics equal for both levels.
TEST(CoarseBins, DrawsAreTheSameWithEitherLevels) {
  const int width = 517, height = 389;
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int layer = 0; layer < 8; ++layer) {
    const float z = 0.1f + 0.1f * float(layer < 4 ? 3 - layer : layer);
    const uint32_t base = uint32_t(vertices.size());
    // Sloped, and reaching past the screen on the left and top.
    vertices.push_back({glm::vec3(-30, -20, z)});
    vertices.push_back({glm::vec3(width, -20, z + 0.05f)});
    vertices.push_back({glm::vec3(width, height, z)});
    vertices.push_back({glm::vec3(-30, height, z - 0.05f)});
    for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + k);
    for (int k = 0; k < 20; ++k) {
      const uint32_t b = uint32_t(vertices.size());
      const float cx = unit(rng) * width, cy = unit(rng) * height, size = 8.0f + 300.0f * unit(rng);
      for (int v = 0; v < 3; ++v)
        vertices.push_back({glm::vec3(cx + size * (unit(rng) - 0.5f),
                                      cy + size * (unit(rng) - 0.5f), unit(rng))});
      for (uint32_t v : {0u, 1u, 2u}) indices.push_back(b + v);
    }
  }
  ExecutionOptions tilesOnly;
  tilesOnly.binLevels = BinLevels::TilesOnly;
  const testing_support::DrawnFrame one = testing_support::drawWindowTriangles(
      width, height, vertices, indices, glm::vec4(0.2f, 0.6f, 0.9f, 1.0f), tilesOnly, true);
  for (const int threads : {1, 2}) {
    ExecutionOptions coarse;
    coarse.threads = threads;
    const testing_support::DrawnFrame two = testing_support::drawWindowTriangles(
        width, height, vertices, indices, glm::vec4(0.2f, 0.6f, 0.9f, 1.0f), coarse, true);
    EXPECT_EQ(two.color, one.color);
    EXPECT_EQ(0, std::memcmp(two.depth.data(), one.depth.data(), one.depth.size() * sizeof(float)));
    EXPECT_EQ(two.counts, one.counts);
    EXPECT_EQ(two.stats, one.stats);
  }
  EXPECT_GT(one.stats.tilesTriviallyAccepted, 8u * (width / 8) * (height / 8) / 2);
}

}  // namespace
}  // namespace rast
