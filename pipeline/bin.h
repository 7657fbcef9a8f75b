// Binning: each set-up triangle into the 8x8-pixel tiles it can touch, in submission order.
//
// Two levels. Every entry names an 8x8 tile, except where a large triangle covers a whole coarse
// tile (8x8 tiles, 64x64 pixels): there it gets one coarse entry instead of 64 tile entries. A
// large triangle is tested per coarse tile first, and per tile only inside the coarse tiles it
// covers partly, so binning it costs in proportion to its edges' length, not its area (W3's
// full-screen layers: one test per 64 tiles). A tile's entries are its own and its coarse tile's,
// merged in submission order (entries()): exactly the list one-level binning makes, flags
// included, so the two levels change no output bit and no counter (tests/coarse_bins_test.cpp).
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

// A coarse tile is (1 << kCoarseShift)^2 tiles.
inline constexpr int kCoarseShift = 3;
inline constexpr int kCoarseTiles = 1 << kCoarseShift;

// Triangle ids grouped by tile. Built from groups of triangles in parallel, then placed by a
// stable counting sort (tile-major, group-minor), so each bin lists its triangles in submission
// order whatever the thread count. Coarse tiles get the same sort of their own.
class TileBins {
 public:
  // `memory`: where the bins and their temporaries are allocated (ExecutionOptions::memory).
  TileBins(int widthPixels, int heightPixels, ScratchMemory* memory = nullptr,
           BinLevels levels = BinLevels::Coarse);

  int tilesX() const { return tilesX_; }
  int tilesY() const { return tilesY_; }
  int tileCount() const { return tilesX_ * tilesY_; }
  // (triangle, tile) pairs, a coarse entry counting once per tile of its coarse tile: the length
  // of every tile's entries() together, whatever the levels.
  size_t entryCount() const { return triangles_.size() + coarseEntryTiles_; }
  // Coarse entries, each standing for the tiles of its coarse tile.
  size_t coarseEntryCount() const { return coarseTriangles_.size(); }

  // The triangles binned to `tile`, in submission order: its tile entries and its coarse tile's
  // entries, merged (in `scratch` when both have some).
  std::span<const uint32_t> entries(int tile, std::vector<uint32_t>& scratch) const;
  // No triangle binned to `tile`, at either level.
  // Forced inline: the tile loop asks it of every tile, and GCC left it a call there.
  [[gnu::always_inline]] bool empty(int tile) const {
    return tileBin(tile).empty() && coarseBin(tile).empty();
  }

  // Bins every triangle of `chunks` (a range of ranges of objects with `edges` and `bounds`),
  // naming triangle i of chunk c by id(c, i). `sampleReach`: see classifyTile. Float mode passes
  // the triangles' float edges, chunk for chunk, in `floatChunks`.
  template <class Chunks, class IdOf>
  void build(const Chunks& chunks, FixedPointFormat format, int32_t sampleReach, IdOf&& id,
             PipelineStatistics& stats,
             const std::vector<ScratchVector<FloatEdges>>* floatChunks = nullptr) {
    const size_t threads = size_t(tbb::this_task_arena::max_concurrency());
    const size_t maxGroups = maxChunkGroups();
    const size_t groupSize = chunksPerGroup(chunks.size());
    const size_t chunkGroups = chunkCount(chunks.size(), groupSize);
    // With several threads, draws of few chunks (W3: 32 full-screen triangles, one chunk) are
    // also split into bands of tile rows, so that their many tiles are binned in parallel (four
    // parts per thread, as groups: two bands per thread measured slower on W3). Part (group,
    // band) is parts[group * bands + band]; a tile lies in one band, so the sort (tile-major, then
    // group) still lists each bin's triangles in submission order.
    // Bands are whole rows of coarse tiles, so that a coarse tile lies in one band too.
    const int bands = chunkGroups == 0 || threads == 1
                          ? 1
                          : int(std::clamp<size_t>(maxGroups / chunkGroups, 1, size_t(coarseY_)));
    const int bandRows = (coarseY_ + bands - 1) / bands * kCoarseTiles;
    const ScratchVector<Entry> empty{ScratchAllocator<Entry>(memory_)};
    std::vector<Part> parts(chunkGroups * size_t(bands), Part{empty, empty, {}});
    tbb::parallel_for(size_t{0}, parts.size(), [&](size_t part) {
      const size_t g = part / size_t(bands);
      const int firstRow = int(part % size_t(bands)) * bandRows;
      const int endRow = std::min(tilesY_, firstRow + bandRows);
      Part& out = parts[part];
      // Every triangle of the group that lies in the band touches at least one tile: reserving
      // one entry per triangle saves the vector most of its doublings (and their copies).
      size_t groupTriangles = 0;
      for (size_t c = g * groupSize; c < std::min(chunks.size(), (g + 1) * groupSize); ++c)
        groupTriangles += chunks[c].size();
      out.tiles.reserve(groupTriangles / size_t(bands) + 16);
      for (size_t c = g * groupSize; c < std::min(chunks.size(), (g + 1) * groupSize); ++c)
        binTriangles(chunks[c], c, id, floatChunks ? &(*floatChunks)[c] : nullptr, format,
                     sampleReach, firstRow, endRow, out);
    });
    // Group g is parts [g * bands, (g + 1) * bands): its bands, which share no tile.
    std::vector<size_t> groupFirst(chunkGroups + 1);
    for (size_t g = 0; g <= chunkGroups; ++g) groupFirst[g] = g * size_t(bands);
    finish(parts, groupFirst, /*disjointWithinGroup=*/true, stats);
  }

  // Binning chunk by chunk, for a front end that bins each chunk of triangles as soon as it has
  // set it up, while the triangles are still in its core's cache: startChunks(count), then
  // binChunk for every chunk (from any thread, in any order), then finishChunks. The bins are
  // those build() makes of the same chunks: each chunk's entries in submission order, placed by
  // the same stable sort.
  void startChunks(size_t chunks) {
    const ScratchVector<Entry> empty{ScratchAllocator<Entry>(memory_)};
    chunkParts_.assign(chunks, Part{empty, empty, {}});
  }
  template <class Chunk, class IdOf>
  void binChunk(size_t c, const Chunk& triangles, FixedPointFormat format, int32_t sampleReach,
                IdOf&& id, const ScratchVector<FloatEdges>* floatEdges = nullptr) {
    Part& out = chunkParts_[c];
    out.tiles.reserve(triangles.size() + 16);
    binTriangles(triangles, c, id, floatEdges, format, sampleReach, 0, tilesY_, out);
  }
  void finishChunks(PipelineStatistics& stats);

 private:
  struct Entry {
    uint32_t tile;
    uint32_t triangle;
  };
  // What one part of the binning (a group of chunks, a band of tile rows) makes.
  struct Part {
    ScratchVector<Entry> tiles;
    ScratchVector<Entry> coarse;  // their tile field names a coarse tile
    PipelineStatistics stats;
  };
  // Appends the tiles of `bounds` (more than one) in tile rows [firstRow, endRow) that the corner
  // test does not reject (of the float edges when given: float mode).
  void addTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                   const FloatEdges* floatEdges, const PixelRect& bounds, FixedPointFormat format,
                   int32_t sampleReach, int firstRow, int endRow, Part& out) const;
  // Tiles [tx0, tx1] x [ty0, ty1] of a triangle too large for one coarse tile: per coarse tile.
  void addLargeTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                        const PixelRect& bounds, FixedPointFormat format, int32_t sampleReach,
                        int tx0, int tx1, int ty0, int ty1, Part& out) const;
  void binTileRect(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                   const PixelRect& bounds, FixedPointFormat format, int32_t sampleReach,
                   int fx0, int fx1, int fy0, int fy1, Part& out) const;
  // build()'s groups of consecutive chunks, a few per thread: each is a task of the binning, so
  // a few per thread balance the load, while the counting sort pays for each group a pass over
  // every tile's counter (finishChunks, whose binning is done, makes one group per thread). The
  // grouping does not change the result: every bin lists its triangles in submission order.
  // Called inside the arena.
  static size_t maxChunkGroups() {
    return std::min<size_t>(64, 4 * size_t(tbb::this_task_arena::max_concurrency()));
  }
  static size_t chunksPerGroup(size_t chunks) {
    return std::max<size_t>(1, (chunks + maxChunkGroups() - 1) / maxChunkGroups());
  }
  // The triangles of `chunk` (chunk c) that lie in tile rows [firstRow, endRow), into `out`.
  template <class Chunk, class IdOf>
  void binTriangles(const Chunk& chunk, size_t c, IdOf& id,
                    const ScratchVector<FloatEdges>* floatEdges, FixedPointFormat format,
                    int32_t sampleReach, int firstRow, int endRow, Part& out) const {
    for (size_t i = 0; i < chunk.size(); ++i) {
      const PixelRect& b = chunk[i].bounds;
      const int tx = b.x0 >> kTileShift, ty = b.y0 >> kTileShift;
      if (tx == (b.x1 - 1) >> kTileShift && ty == (b.y1 - 1) >> kTileShift) {
        // A one-tile triangle is not tested: its bounds already say it touches the tile.
        if (ty >= firstRow && ty < endRow)
          out.tiles.push_back({uint32_t(ty * tilesX_ + tx), id(c, i)});
        continue;
      }
      addTriangle(id(c, i), chunk[i].edges, floatEdges ? &(*floatEdges)[i] : nullptr, b, format,
                  sampleReach, firstRow, endRow, out);
    }
  }
  // Both sorts of the parts' entries, group g being parts [groupFirst[g], groupFirst[g + 1]) in
  // submission order, and the parts' statistics added to `stats`.
  void finish(const std::vector<Part>& parts, std::span<const size_t> groupFirst,
              bool disjointWithinGroup, PipelineStatistics& stats);
  // Counting sort of the parts' `list` (tile-major, then group) into
  // triangles[offsets[t], offsets[t + 1]). The parts of a group are counted in order by one
  // task, or in parallel when they share no tile (bands).
  void sortByTile(const std::vector<Part>& parts, ScratchVector<Entry> Part::*list,
                  std::span<const size_t> groupFirst, bool disjointWithinGroup, size_t tiles,
                  ScratchVector<uint32_t>& offsets, ScratchVector<uint32_t>& triangles);
  [[gnu::always_inline]] std::span<const uint32_t> tileBin(int tile) const {
    return {triangles_.data() + offsets_[tile], triangles_.data() + offsets_[tile + 1]};
  }
  [[gnu::always_inline]] std::span<const uint32_t> coarseBin(int tile) const {
    const int c = (tile / tilesX_ >> kCoarseShift) * coarseX_ + (tile % tilesX_ >> kCoarseShift);
    return {coarseTriangles_.data() + coarseOffsets_[c],
            coarseTriangles_.data() + coarseOffsets_[c + 1]};
  }

  int tilesX_, tilesY_;
  int coarseX_, coarseY_;
  BinLevels levels_;
  ScratchMemory* memory_;
  ScratchVector<uint32_t> offsets_;    // bin t is triangles_[offsets_[t], offsets_[t + 1])
  ScratchVector<uint32_t> triangles_;
  ScratchVector<uint32_t> coarseOffsets_;  // the same for coarse tiles
  ScratchVector<uint32_t> coarseTriangles_;
  size_t coarseEntryTiles_ = 0;
  std::vector<Part> chunkParts_;  // startChunks .. finishChunks
};

}  // namespace rast
