// Binning: each set-up triangle into the 8x8-pixel tiles it can touch, in submission order.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/execution.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "rasterizer/coverage.h"
#include "rasterizer/float_coverage.h"

namespace rast {

// Triangle indices grouped by tile. Built from chunks of triangles in parallel, then placed by a
// stable counting sort (tile-major, chunk-minor), so each bin lists its triangles in submission
// order whatever the thread count.
class TileBins {
 public:
  TileBins(int widthPixels, int heightPixels);

  int tilesX() const { return tilesX_; }
  int tilesY() const { return tilesY_; }
  int tileCount() const { return tilesX_ * tilesY_; }
  size_t entryCount() const { return triangles_.size(); }

  std::span<const uint32_t> bin(int tile) const {
    return {triangles_.data() + offsets_[tile], triangles_.data() + offsets_[tile + 1]};
  }

  // Bins triangles [0, count); triangle(i) returns an object with `edges`, `floatEdges` and
  // `bounds`.
  template <class TriangleAt>
  void build(size_t count, FixedPointFormat format, TriangleAt&& triangle,
             PipelineStatistics& stats, RasterMode mode = RasterMode::FixedPoint) {
    // At most 64 chunks: the counting sort keeps a count per (chunk, tile).
    const size_t chunkSize = std::max<size_t>(1024, (count + 63) / 64);
    std::vector<ScratchVector<Entry>> entries(chunkCount(count, chunkSize));
    std::vector<PipelineStatistics> chunkStats(entries.size());
    forEachChunk(count, chunkSize, [&](size_t c, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        const auto& t = triangle(i);
        addTriangle(uint32_t(i), t.edges, mode == RasterMode::Float ? &t.floatEdges : nullptr,
                    t.bounds, format, entries[c], chunkStats[c]);
      }
    });
    for (const PipelineStatistics& s : chunkStats) stats += s;
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
                   ScratchVector<Entry>& out, PipelineStatistics& stats) const;
  void sortByTile(const std::vector<ScratchVector<Entry>>& chunks);

  int tilesX_, tilesY_;
  ScratchVector<uint32_t> offsets_;    // bin t is triangles_[offsets_[t], offsets_[t + 1])
  ScratchVector<uint32_t> triangles_;
};

}  // namespace rast
