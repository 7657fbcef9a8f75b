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

// classifyTile's corner test for a rectangle of tiles, stepped from tile to tile: per edge, the
// largest and smallest values over the rectangle's (reach-widened) sample positions are E at its
// top-left sample corner plus constants.
struct CornerTest {
  std::array<int64_t, 3> stepX, stepY;      // E from one tile to the next
  std::array<int64_t, 3> highest, lowest;   // over one tile's samples, from its corner
  const std::array<EdgeFunction, 3>* edges;
  FixedPointFormat format;
  int32_t reach;

  CornerTest(const std::array<EdgeFunction, 3>& e, FixedPointFormat f, int32_t sampleReach)
      : edges(&e), format(f), reach(sampleReach) {
    const int64_t tileStep = int64_t(kTileSize) << f.fractionBits;
    for (int i = 0; i < 3; ++i) {
      stepX[i] = int64_t{e[i].a} * tileStep;
      stepY[i] = int64_t{e[i].b} * tileStep;
      highest[i] = extreme(i, kTileSize, kTileSize, true);
      lowest[i] = extreme(i, kTileSize, kTileSize, false);
    }
  }

  // E of edge i at the top-left (reach-widened) sample corner of tile (tx, ty).
  int64_t corner(int i, int tx, int ty) const {
    return (*edges)[i].at(pixelCentreSubpixels(tx * kTileSize, format) - reach,
                          pixelCentreSubpixels(ty * kTileSize, format) - reach);
  }
  // The largest (or smallest) of E minus its corner value over the samples of a rectangle of
  // `cols` x `rows` tiles.
  int64_t extreme(int i, int colsPixels, int rowsPixels, bool largest) const {
    const int64_t spanX = (int64_t(colsPixels - 1) << format.fractionBits) + 2 * int64_t(reach);
    const int64_t spanY = (int64_t(rowsPixels - 1) << format.fractionBits) + 2 * int64_t(reach);
    const int64_t ax = int64_t{(*edges)[i].a} * spanX, by = int64_t{(*edges)[i].b} * spanY;
    return largest ? std::max<int64_t>(ax, 0) + std::max<int64_t>(by, 0)
                   : std::min<int64_t>(ax, 0) + std::min<int64_t>(by, 0);
  }
};

// The tile rectangle [tx0, tx1] x [ty0, ty1] (inclusive) lies within `bounds`.
bool withinBounds(const PixelRect& bounds, int tx0, int tx1, int ty0, int ty1) {
  return tx0 * kTileSize >= bounds.x0 && (tx1 + 1) * kTileSize <= bounds.x1 &&
         ty0 * kTileSize >= bounds.y0 && (ty1 + 1) * kTileSize <= bounds.y1;
}

}  // namespace

void TileBins::addTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                           const FloatEdges* floatEdges, const PixelRect& bounds,
                           FixedPointFormat format, int32_t sampleReach, int firstRow,
                           int endRow, ScratchVector<Entry>& out, ScratchVector<Entry>& coarseOut,
                           PipelineStatistics& stats) const {
  const int tx0 = bounds.x0 >> kTileShift, tx1 = (bounds.x1 - 1) >> kTileShift;
  const int boundsTy0 = bounds.y0 >> kTileShift, boundsTy1 = (bounds.y1 - 1) >> kTileShift;
  // The triangle's tile rows within the band.
  const int ty0 = std::max(boundsTy0, firstRow), ty1 = std::min(boundsTy1, endRow - 1);
  if (ty0 > ty1) return;
  if (tx0 == tx1 && boundsTy0 == boundsTy1) {
    // A one-tile triangle is not tested here: its bounds already say it touches the tile.
    out.push_back({uint32_t(ty0 * tilesX_ + tx0), triangle});
    return;
  }
  if (floatEdges) {
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) {
        if (classifyTileFloat(*floatEdges, bounds, tx, ty) == TileCoverage::Outside)
          ++stats.tilesTriviallyRejected;
        else
          out.push_back({uint32_t(ty * tilesX_ + tx), triangle});
      }
    return;
  }
  const CornerTest test(edges, format, sampleReach);

  // Tiles [fx0, fx1] x [fy0, fy1], each by the corner test.
  auto binTiles = [&](int fx0, int fx1, int fy0, int fy1) {
    std::array<int64_t, 3> rowStart;
    for (int i = 0; i < 3; ++i) rowStart[i] = test.corner(i, fx0, fy0);
    for (int ty = fy0; ty <= fy1; ++ty) {
      std::array<int64_t, 3> e = rowStart;
      for (int tx = fx0; tx <= fx1; ++tx) {
        if (e[0] + test.highest[0] < 0 || e[1] + test.highest[1] < 0 ||
            e[2] + test.highest[2] < 0) {
          ++stats.tilesTriviallyRejected;
        } else {
          // Inside: every edge non-negative over the tile's samples, and the tile within the
          // bounds (classifyTile's Inside, which coverTile would find for every sample).
          const bool whole = e[0] + test.lowest[0] >= 0 && e[1] + test.lowest[1] >= 0 &&
                             e[2] + test.lowest[2] >= 0 && withinBounds(bounds, tx, tx, ty, ty);
          out.push_back({uint32_t(ty * tilesX_ + tx), whole ? triangle | kWholeTileBit : triangle});
        }
        for (int i = 0; i < 3; ++i) e[i] += test.stepX[i];
      }
      for (int i = 0; i < 3; ++i) rowStart[i] += test.stepY[i];
    }
  };

  // Only a triangle whose bounds reach across two coarse tiles each way can contain a whole one
  // (any 128 aligned pixels hold 64 aligned ones); smaller ones go tile by tile.
  constexpr int kCoarsePixels = kCoarseTiles * kTileSize;
  if (levels_ == BinLevels::TilesOnly || bounds.x1 - bounds.x0 < 2 * kCoarsePixels ||
      bounds.y1 - bounds.y0 < 2 * kCoarsePixels) {
    binTiles(tx0, tx1, ty0, ty1);
    return;
  }
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
      const int colsPixels = (fx1 - fx0 + 1) * kTileSize, rowsPixels = (fy1 - fy0 + 1) * kTileSize;
      bool outside = false, inside = true;
      for (int i = 0; i < 3; ++i) {
        const int64_t e = test.corner(i, fx0, fy0);
        outside |= e + test.extreme(i, colsPixels, rowsPixels, true) < 0;
        inside &= e + test.extreme(i, colsPixels, rowsPixels, false) >= 0;
      }
      if (outside) {
        stats.tilesTriviallyRejected += uint64_t(fx1 - fx0 + 1) * uint64_t(fy1 - fy0 + 1);
      } else if (inside && fx0 == cx * kCoarseTiles && fx1 == coarseX1 &&
                 fy0 == cy * kCoarseTiles && fy1 == coarseY1 &&
                 withinBounds(bounds, fx0, fx1, fy0, fy1)) {
        coarseOut.push_back({uint32_t(cy * coarseX_ + cx), triangle | kWholeTileBit});
      } else {
        binTiles(fx0, fx1, fy0, fy1);
      }
    }
}

void TileBins::sortByTile(const std::vector<ScratchVector<Entry>>& parts, size_t tiles,
                          ScratchVector<uint32_t>& offsets, ScratchVector<uint32_t>& triangles) {
  // Per (part, tile): the count, then the next slot.
  ScratchVector<uint32_t> cursor(parts.size() * tiles, 0, ScratchAllocator<uint32_t>(memory_));
  tbb::parallel_for(size_t{0}, parts.size(), [&](size_t c) {
    for (const Entry& e : parts[c]) ++cursor[c * tiles + e.tile];
  });
  offsets[0] = 0;
  for (size_t t = 0; t < tiles; ++t) {
    uint32_t total = 0;
    for (size_t c = 0; c < parts.size(); ++c) total += cursor[c * tiles + t];
    offsets[t + 1] = offsets[t] + total;
  }
  tbb::parallel_for(size_t{0}, tiles, [&](size_t t) {
    uint32_t slot = offsets[t];
    for (size_t c = 0; c < parts.size(); ++c) {
      const uint32_t n = cursor[c * tiles + t];
      cursor[c * tiles + t] = slot;
      slot += n;
    }
  });
  triangles.resize(offsets[tiles]);
  tbb::parallel_for(size_t{0}, parts.size(), [&](size_t c) {
    for (const Entry& e : parts[c]) triangles[cursor[c * tiles + e.tile]++] = e.triangle;
  });
}

}  // namespace rast
