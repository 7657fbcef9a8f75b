#include "pipeline/bin.h"

#include <algorithm>

namespace rast {

TileBins::TileBins(int widthPixels, int heightPixels, ScratchMemory* memory, BinLevels levels)
    : tilesX_((widthPixels + kTileSize - 1) / kTileSize),
      tilesY_((heightPixels + kTileSize - 1) / kTileSize),
      coarseX_((tilesX_ + kCoarseTiles - 1) / kCoarseTiles),
      coarseY_((tilesY_ + kCoarseTiles - 1) / kCoarseTiles),
      levels_(levels),
      memory_(memory),
      offsets_(size_t(tilesX_) * size_t(tilesY_) + 1, 0, ScratchAllocator<uint32_t>(memory)),
      triangles_(ScratchAllocator<uint32_t>(memory)),
      coarseOffsets_(size_t(coarseX_) * size_t(coarseY_) + 1, 0,
                     ScratchAllocator<uint32_t>(memory)),
      coarseTriangles_(ScratchAllocator<uint32_t>(memory)) {}

std::span<const uint32_t> TileBins::entries(int tile, std::vector<uint32_t>& scratch) const {
  const std::span<const uint32_t> own = tileBin(tile), coarse = coarseBin(tile);
  if (coarse.empty()) return own;
  if (own.empty()) return coarse;
  // A triangle is in one of the two lists of a tile, never both; ids grow in submission order.
  scratch.resize(own.size() + coarse.size());
  std::merge(own.begin(), own.end(), coarse.begin(), coarse.end(), scratch.begin(),
             [](uint32_t a, uint32_t b) { return (a & ~kWholeTileBit) < (b & ~kWholeTileBit); });
  return scratch;
}

namespace {

// Tile (tx, ty) lies within `bounds`.
bool tileWithinBounds(const PixelRect& bounds, int tx, int ty) {
  return tx * kTileSize >= bounds.x0 && (tx + 1) * kTileSize <= bounds.x1 &&
         ty * kTileSize >= bounds.y0 && (ty + 1) * kTileSize <= bounds.y1;
}

}  // namespace

// Tiles [fx0, fx1] x [fy0, fy1] of `bounds`, each by the corner test, stepped from tile to tile.
// Inlined into both callers: as a call of its own, small triangles binned 10 % slower.
[[gnu::always_inline]] inline void TileBins::binTileRect(
    uint32_t triangle, const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
    FixedPointFormat format, int32_t sampleReach, int fx0, int fx1, int fy0, int fy1,
    Part& part) const {
  // classifyTile, stepped from tile to tile: E at each tile's top-left (reach-widened) sample
  // corner, plus per edge its extent over a tile.
  const int64_t sx0 = pixelCentreSubpixels(fx0 * kTileSize, format) - sampleReach;
  const int64_t sy0 = pixelCentreSubpixels(fy0 * kTileSize, format) - sampleReach;
  const int64_t tileStep = int64_t(kTileSize) << format.fractionBits;
  std::array<int64_t, 3> rowStart, stepX, stepY, highest, lowest;
  for (int i = 0; i < 3; ++i) {
    rowStart[i] = edges[i].at(sx0, sy0);
    stepX[i] = int64_t{edges[i].a} * tileStep;
    stepY[i] = int64_t{edges[i].b} * tileStep;
    const EdgeExtent extent = edgeExtent(edges[i], kTileSize, kTileSize, format, sampleReach);
    highest[i] = extent.highest;
    lowest[i] = extent.lowest;
  }
  for (int ty = fy0; ty <= fy1; ++ty) {
    std::array<int64_t, 3> e = rowStart;
    for (int tx = fx0; tx <= fx1; ++tx) {
      if (e[0] + highest[0] < 0 || e[1] + highest[1] < 0 || e[2] + highest[2] < 0) {
        ++part.stats.tilesTriviallyRejected;
      } else {
        // Inside: every edge non-negative over the tile's samples, and the tile within the
        // bounds (classifyTile's Inside, which coverTile would find for every sample).
        const bool whole = e[0] + lowest[0] >= 0 && e[1] + lowest[1] >= 0 &&
                           e[2] + lowest[2] >= 0 && tileWithinBounds(bounds, tx, ty);
        part.tiles.push_back(
            {uint32_t(ty * tilesX_ + tx), whole ? triangle | kWholeTileBit : triangle});
      }
      for (int i = 0; i < 3; ++i) e[i] += stepX[i];
    }
    for (int i = 0; i < 3; ++i) rowStart[i] += stepY[i];
  }
}

void TileBins::addTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                           const FloatEdges* floatEdges, const PixelRect& bounds,
                           FixedPointFormat format, int32_t sampleReach, int firstRow,
                           int endRow, Part& part) const {
  const int tx0 = bounds.x0 >> kTileShift, tx1 = (bounds.x1 - 1) >> kTileShift;
  const int boundsTy0 = bounds.y0 >> kTileShift, boundsTy1 = (bounds.y1 - 1) >> kTileShift;
  // The triangle's tile rows within the band.
  const int ty0 = std::max(boundsTy0, firstRow), ty1 = std::min(boundsTy1, endRow - 1);
  if (ty0 > ty1) return;
  if (floatEdges) {
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) {
        if (classifyTileFloat(*floatEdges, bounds, tx, ty) == TileCoverage::Outside)
          ++part.stats.tilesTriviallyRejected;
        else
          part.tiles.push_back({uint32_t(ty * tilesX_ + tx), triangle});
      }
    return;
  }
  // Only a triangle whose bounds reach across two coarse tiles each way can contain a whole one
  // (any 128 aligned pixels hold 64 aligned ones); smaller ones go tile by tile.
  constexpr int kCoarsePixels = kCoarseTiles * kTileSize;
  if (levels_ == BinLevels::Coarse && bounds.x1 - bounds.x0 >= 2 * kCoarsePixels &&
      bounds.y1 - bounds.y0 >= 2 * kCoarsePixels)
    addLargeTriangle(triangle, edges, bounds, format, sampleReach, tx0, tx1, ty0, ty1, part);
  else
    binTileRect(triangle, edges, bounds, format, sampleReach, tx0, tx1, ty0, ty1, part);
}

void TileBins::addLargeTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                                const PixelRect& bounds, FixedPointFormat format,
                                int32_t sampleReach, int tx0, int tx1, int ty0, int ty1,
                                Part& part) const {
  // The same test over a coarse tile's part of the bounds decides all its tiles at once: an edge
  // negative at every sample of the part is negative at every sample of each tile in it, so the
  // per-tile test would reject each (and counts them so); every edge non-negative at every
  // sample of a whole coarse tile within the bounds makes each of its tiles one the per-tile
  // test flags whole. Either way the tiles get the entries per-tile binning gives them.
  for (int cy = ty0 >> kCoarseShift; cy <= ty1 >> kCoarseShift; ++cy)
    for (int cx = tx0 >> kCoarseShift; cx <= tx1 >> kCoarseShift; ++cx) {
      const int coarseX1 = std::min(cx * kCoarseTiles + kCoarseTiles, tilesX_) - 1;
      const int coarseY1 = std::min(cy * kCoarseTiles + kCoarseTiles, tilesY_) - 1;
      const int fx0 = std::max(tx0, cx * kCoarseTiles), fx1 = std::min(tx1, coarseX1);
      const int fy0 = std::max(ty0, cy * kCoarseTiles), fy1 = std::min(ty1, coarseY1);
      const TileCoverage coverage =
          classifyTiles(edges, bounds, fx0, fx1, fy0, fy1, format, sampleReach);
      if (coverage == TileCoverage::Outside) {
        part.stats.tilesTriviallyRejected += uint64_t(fx1 - fx0 + 1) * uint64_t(fy1 - fy0 + 1);
      } else if (coverage == TileCoverage::Inside && fx0 == cx * kCoarseTiles &&
                 fx1 == coarseX1 && fy0 == cy * kCoarseTiles && fy1 == coarseY1) {
        part.coarse.push_back({uint32_t(cy * coarseX_ + cx), triangle | kWholeTileBit});
      } else {
        binTileRect(triangle, edges, bounds, format, sampleReach, fx0, fx1, fy0, fy1, part);
      }
    }
}

void TileBins::finishChunks(PipelineStatistics& stats) {
  // Groups of consecutive chunks: a group's chunks share tiles, so one task counts them, in
  // order. One group per thread, not build()'s few per thread: the binning is done, and here a
  // group only costs the sort a pass over every tile's counter in each of its phases. Against
  // build()'s grouping (four a thread), the sort took 0.77x the time on W4 and 0.65x on W2
  // tiny-10 at 2 threads, 0.88x at 1 (bench/compare_builds.py, five pairs).
  const size_t chunks = chunkParts_.size();
  const size_t threads = size_t(tbb::this_task_arena::max_concurrency());
  const size_t groupSize = std::max<size_t>(1, (chunks + threads - 1) / threads);
  std::vector<size_t> groupFirst;
  for (size_t c = 0; c < chunks; c += groupSize) groupFirst.push_back(c);
  groupFirst.push_back(chunks);
  finish(chunkParts_, groupFirst, /*disjointWithinGroup=*/false, stats);
  chunkParts_.clear();
}

void TileBins::finish(const std::vector<Part>& parts, std::span<const size_t> groupFirst,
                      bool disjointWithinGroup, PipelineStatistics& stats) {
  for (const Part& p : parts) stats += p.stats;
  sortByTile(parts, &Part::tiles, groupFirst, disjointWithinGroup, size_t(tileCount()), offsets_,
             triangles_);
  coarseEntryTiles_ = 0;
  coarseTriangles_.clear();
  std::fill(coarseOffsets_.begin(), coarseOffsets_.end(), 0u);
  if (std::all_of(parts.begin(), parts.end(), [](const Part& p) { return p.coarse.empty(); }))
    return;
  sortByTile(parts, &Part::coarse, groupFirst, disjointWithinGroup,
             size_t(coarseX_) * size_t(coarseY_), coarseOffsets_, coarseTriangles_);
  for (int c = 0; c < coarseX_ * coarseY_; ++c) {
    const int cx = c % coarseX_, cy = c / coarseX_;
    const size_t tiles = size_t(std::min(kCoarseTiles, tilesX_ - cx * kCoarseTiles)) *
                         size_t(std::min(kCoarseTiles, tilesY_ - cy * kCoarseTiles));
    coarseEntryTiles_ += tiles * (coarseOffsets_[c + 1] - coarseOffsets_[c]);
  }
}

void TileBins::sortByTile(const std::vector<Part>& parts, ScratchVector<Entry> Part::*list,
                          std::span<const size_t> groupFirst, bool disjointWithinGroup,
                          size_t tiles, ScratchVector<uint32_t>& offsets,
                          ScratchVector<uint32_t>& triangles) {
  // Per (group, tile): the count, then the next slot. Counting per group instead of per part
  // keeps the order (a group's parts are in submission order, or share no tile) and makes the
  // serial pass shorter.
  const size_t groups = groupFirst.size() - 1;
  std::vector<uint32_t> groupOf(parts.size());
  for (size_t g = 0; g < groups; ++g)
    std::fill(groupOf.begin() + ptrdiff_t(groupFirst[g]),
              groupOf.begin() + ptrdiff_t(groupFirst[g + 1]), uint32_t(g));
  // Parts of one group in parallel only where they share no tile; else a group's parts in order.
  auto eachPart = [&](auto&& f) {
    if (disjointWithinGroup)
      tbb::parallel_for(size_t{0}, parts.size(), f);
    else
      tbb::parallel_for(size_t{0}, groups, [&](size_t g) {
        for (size_t p = groupFirst[g]; p != groupFirst[g + 1]; ++p) f(p);
      });
  };
  ScratchVector<uint32_t> cursor(groups * tiles, 0, ScratchAllocator<uint32_t>(memory_));
  eachPart([&](size_t p) {
    uint32_t* group = cursor.data() + groupOf[p] * tiles;
    for (const Entry& e : parts[p].*list) ++group[e.tile];
  });
  offsets[0] = 0;
  for (size_t t = 0; t < tiles; ++t) {
    uint32_t total = 0;
    for (size_t g = 0; g < groups; ++g) total += cursor[g * tiles + t];
    offsets[t + 1] = offsets[t] + total;
  }
  tbb::parallel_for(size_t{0}, tiles, [&](size_t t) {
    uint32_t slot = offsets[t];
    for (size_t g = 0; g < groups; ++g) {
      const uint32_t n = cursor[g * tiles + t];
      cursor[g * tiles + t] = slot;
      slot += n;
    }
  });
  triangles.resize(offsets[tiles]);
  eachPart([&](size_t p) {
    uint32_t* group = cursor.data() + groupOf[p] * tiles;
    for (const Entry& e : parts[p].*list) triangles[group[e.tile]++] = e.triangle;
  });
}

}  // namespace rast
