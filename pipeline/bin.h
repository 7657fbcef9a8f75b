// Binning: each set-up triangle into the 8x8-pixel tiles it can touch, in submission order.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <tbb/task_arena.h>

#include "pipeline/execution.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "rasterizer/coverage.h"
#include "rasterizer/float_coverage.h"

namespace rast {

// A bin entry is a triangle id (below 2^31) with kWholeTileBit set when the binning corner test
// found every sample of the tile inside the triangle, so the back end skips its coverage test.
inline constexpr uint32_t kWholeTileBit = uint32_t{1} << 31;

// Triangle ids grouped by tile. Built from groups of triangles in parallel, then placed by a
// stable counting sort (tile-major, group-minor), so each bin lists its triangles in submission
// order whatever the thread count.
class TileBins {
 public:
  // `memory`: where the bins and their temporaries are allocated (ExecutionOptions::memory).
  TileBins(int widthPixels, int heightPixels, ScratchMemory* memory = nullptr);

  int tilesX() const { return tilesX_; }
  int tilesY() const { return tilesY_; }
  int tileCount() const { return tilesX_ * tilesY_; }
  size_t entryCount() const { return triangles_.size(); }

  std::span<const uint32_t> bin(int tile) const {
    return {triangles_.data() + offsets_[tile], triangles_.data() + offsets_[tile + 1]};
  }

  // Bins every triangle of `chunks` (a range of ranges of objects with `edges` and `bounds`),
  // naming triangle i of chunk c by id(c, i). `sampleReach`: see classifyTile. Float mode passes
  // the triangles' float edges, chunk for chunk, in `floatChunks`.
  template <class Chunks, class IdOf>
  void build(const Chunks& chunks, FixedPointFormat format, int32_t sampleReach, IdOf&& id,
             PipelineStatistics& stats,
             const std::vector<ScratchVector<FloatEdges>>* floatChunks = nullptr) {
    // Groups of consecutive chunks, a few per thread: the counting sort keeps a count per
    // (group, tile), so more groups than threads only cost memory. The grouping does not change
    // the result: every bin lists its triangles in submission order.
    const size_t maxGroups =
        std::min<size_t>(64, 4 * size_t(tbb::this_task_arena::max_concurrency()));
    const size_t groupSize = std::max<size_t>(1, (chunks.size() + maxGroups - 1) / maxGroups);
    std::vector<ScratchVector<Entry>> entries(chunkCount(chunks.size(), groupSize),
                                              ScratchVector<Entry>(ScratchAllocator<Entry>(memory_)));
    std::vector<PipelineStatistics> groupStats(entries.size());
    forEachChunk(chunks.size(), groupSize, [&](size_t g, size_t begin, size_t end) {
      for (size_t c = begin; c < end; ++c)
        for (size_t i = 0; i < chunks[c].size(); ++i)
          addTriangle(id(c, i), chunks[c][i].edges,
                      floatChunks ? &(*floatChunks)[c][i] : nullptr,
                      chunks[c][i].bounds, format, sampleReach, entries[g], groupStats[g]);
    });
    for (const PipelineStatistics& s : groupStats) stats += s;
    sortByTile(entries);
  }

 private:
  struct Entry {
    uint32_t tile;
    uint32_t triangle;
  };
  // Appends the tiles of `bounds` that the corner test does not reject (of the float edges when
  // given: float mode).
  void addTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                   const FloatEdges* floatEdges, const PixelRect& bounds, FixedPointFormat format,
                   int32_t sampleReach, ScratchVector<Entry>& out, PipelineStatistics& stats) const;
  void sortByTile(const std::vector<ScratchVector<Entry>>& chunks);

  int tilesX_, tilesY_;
  ScratchMemory* memory_;
  ScratchVector<uint32_t> offsets_;    // bin t is triangles_[offsets_[t], offsets_[t + 1])
  ScratchVector<uint32_t> triangles_;
};

}  // namespace rast
