#include "pipeline/bin.h"

#include <algorithm>

namespace rast {

TileBins::TileBins(int widthPixels, int heightPixels, ScratchMemory* memory)
    : tilesX_((widthPixels + kTileSize - 1) / kTileSize),
      tilesY_((heightPixels + kTileSize - 1) / kTileSize),
      memory_(memory),
      offsets_(size_t(tilesX_) * size_t(tilesY_) + 1, 0, ScratchAllocator<uint32_t>(memory)),
      triangles_(ScratchAllocator<uint32_t>(memory)) {}

void TileBins::addTriangle(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                           const FloatEdges* floatEdges, const PixelRect& bounds,
                           FixedPointFormat format, int32_t sampleReach, int firstRow,
                           int endRow, ScratchVector<Entry>& out,
                           PipelineStatistics& stats) const {
  const int tx0 = bounds.x0 >> kTileShift, tx1 = (bounds.x1 - 1) >> kTileShift;
  const int boundsTy0 = bounds.y0 >> kTileShift, boundsTy1 = (bounds.y1 - 1) >> kTileShift;
  // The triangle's tile rows within the band; corner values start from the band's first row.
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
  // classifyTile, stepped from tile to tile: per edge, its largest and smallest values over a
  // tile's (reach-widened) sample rectangle are E at the rectangle's corner plus constants.
  const int64_t span = (int64_t(kTileSize - 1) << format.fractionBits) + 2 * int64_t(sampleReach);
  const int64_t tileStep = int64_t(kTileSize) << format.fractionBits;
  std::array<int64_t, 3> rowStart, stepX, stepY, highest, lowest;
  const int64_t sx0 = pixelCentreSubpixels(tx0 * kTileSize, format) - sampleReach;
  const int64_t sy0 = pixelCentreSubpixels(ty0 * kTileSize, format) - sampleReach;
  for (int i = 0; i < 3; ++i) {
    rowStart[i] = edges[i].at(sx0, sy0);
    stepX[i] = int64_t{edges[i].a} * tileStep;
    stepY[i] = int64_t{edges[i].b} * tileStep;
    highest[i] = std::max<int64_t>(int64_t{edges[i].a} * span, 0) +
                 std::max<int64_t>(int64_t{edges[i].b} * span, 0);
    lowest[i] = std::min<int64_t>(int64_t{edges[i].a} * span, 0) +
                std::min<int64_t>(int64_t{edges[i].b} * span, 0);
  }
  for (int ty = ty0; ty <= ty1; ++ty) {
    std::array<int64_t, 3> e = rowStart;
    for (int tx = tx0; tx <= tx1; ++tx) {
      if (e[0] + highest[0] < 0 || e[1] + highest[1] < 0 || e[2] + highest[2] < 0) {
        ++stats.tilesTriviallyRejected;
      } else {
        // Inside: every edge non-negative over the tile's samples, and the tile within the
        // bounds (classifyTile's Inside, which coverTile would find for every sample).
        const bool whole = e[0] + lowest[0] >= 0 && e[1] + lowest[1] >= 0 &&
                           e[2] + lowest[2] >= 0 && tx * kTileSize >= bounds.x0 &&
                           (tx + 1) * kTileSize <= bounds.x1 && ty * kTileSize >= bounds.y0 &&
                           (ty + 1) * kTileSize <= bounds.y1;
        out.push_back({uint32_t(ty * tilesX_ + tx), whole ? triangle | kWholeTileBit : triangle});
      }
      for (int i = 0; i < 3; ++i) e[i] += stepX[i];
    }
    for (int i = 0; i < 3; ++i) rowStart[i] += stepY[i];
  }
}

void TileBins::sortByTile(const std::vector<ScratchVector<Entry>>& chunks) {
  const size_t tiles = size_t(tileCount());
  ScratchVector<uint32_t> cursor(chunks.size() * tiles, 0, ScratchAllocator<uint32_t>(memory_));  // per (chunk, tile): count, then slot
  tbb::parallel_for(size_t{0}, chunks.size(), [&](size_t c) {
    for (const Entry& e : chunks[c]) ++cursor[c * tiles + e.tile];
  });
  offsets_[0] = 0;
  for (size_t t = 0; t < tiles; ++t) {
    uint32_t total = 0;
    for (size_t c = 0; c < chunks.size(); ++c) total += cursor[c * tiles + t];
    offsets_[t + 1] = offsets_[t] + total;
  }
  tbb::parallel_for(size_t{0}, tiles, [&](size_t t) {
    uint32_t slot = offsets_[t];
    for (size_t c = 0; c < chunks.size(); ++c) {
      const uint32_t n = cursor[c * tiles + t];
      cursor[c * tiles + t] = slot;
      slot += n;
    }
  });
  triangles_.resize(offsets_[tiles]);
  tbb::parallel_for(size_t{0}, chunks.size(), [&](size_t c) {
    for (const Entry& e : chunks[c]) triangles_[cursor[c * tiles + e.tile]++] = e.triangle;
  });
}

}  // namespace rast
