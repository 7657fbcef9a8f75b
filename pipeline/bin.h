// Binning: each set-up triangle into the 8x8-pixel tiles it can touch, in submission order.
#pragma once

#include <algorithm>
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
    const size_t threads = size_t(tbb::this_task_arena::max_concurrency());
    const size_t maxGroups = std::min<size_t>(64, 4 * threads);
    const size_t groupSize = std::max<size_t>(1, (chunks.size() + maxGroups - 1) / maxGroups);
    const size_t chunkGroups = chunkCount(chunks.size(), groupSize);
    // With several threads, draws of few chunks (W3: 32 full-screen triangles, one chunk) are
    // also split into bands of tile rows, so that their many tiles are binned in parallel (four
    // parts per thread, as groups: two bands per thread measured slower on W3). Part (group,
    // band) is entries index group * bands + band; a tile lies in one band, so the sort
    // (tile-major, then part) still lists each bin's triangles in submission order.
    const int bands = chunkGroups == 0 || threads == 1
                          ? 1
                          : int(std::clamp<size_t>(maxGroups / chunkGroups, 1, size_t(tilesY_)));
    const int bandRows = (tilesY_ + bands - 1) / bands;
    std::vector<ScratchVector<Entry>> entries(chunkGroups * size_t(bands),
                                              ScratchVector<Entry>(ScratchAllocator<Entry>(memory_)));
    std::vector<PipelineStatistics> partStats(entries.size());
    tbb::parallel_for(size_t{0}, entries.size(), [&](size_t part) {
      const size_t g = part / size_t(bands);
      const int firstRow = int(part % size_t(bands)) * bandRows;
      const int endRow = std::min(tilesY_, firstRow + bandRows);
      for (size_t c = g * groupSize; c < std::min(chunks.size(), (g + 1) * groupSize); ++c)
        for (size_t i = 0; i < chunks[c].size(); ++i)
          addTriangle(id(c, i), chunks[c][i].edges,
                      floatChunks ? &(*floatChunks)[c][i] : nullptr, chunks[c][i].bounds,
                      format, sampleReach, firstRow, endRow, entries[part], partStats[part]);
    });
    for (const PipelineStatistics& s : partStats) stats += s;
    sortByTile(entries);
  }

 private:
  struct Entry {
    uint32_t tile;
    uint32_t triangle;
  };
  // Appends the tiles of `bounds` in tile rows [firstRow, endRow) that the corner test does not
  // reject (of the float edges when given: float mode).
  void addTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                   const FloatEdges* floatEdges, const PixelRect& bounds, FixedPointFormat format,
                   int32_t sampleReach, int firstRow, int endRow, ScratchVector<Entry>& out,
                   PipelineStatistics& stats) const;
  void sortByTile(const std::vector<ScratchVector<Entry>>& chunks);

  int tilesX_, tilesY_;
  ScratchMemory* memory_;
  ScratchVector<uint32_t> offsets_;    // bin t is triangles_[offsets_[t], offsets_[t + 1])
  ScratchVector<uint32_t> triangles_;
};

}  // namespace rast
