#include "pipeline/bin.h"

namespace rast {

TileBins::TileBins(int widthPixels, int heightPixels)
    : tilesX_((widthPixels + kTileSize - 1) / kTileSize),
      tilesY_((heightPixels + kTileSize - 1) / kTileSize) {}

void TileBins::add(uint32_t triangle, const std::array<EdgeFunction, 3>& edges,
                   const PixelRect& bounds, FixedPointFormat format, PipelineStatistics& stats) {
  const int tx0 = bounds.x0 >> kTileShift, tx1 = (bounds.x1 - 1) >> kTileShift;
  const int ty0 = bounds.y0 >> kTileShift, ty1 = (bounds.y1 - 1) >> kTileShift;
  const bool singleTile = tx0 == tx1 && ty0 == ty1;
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      // A one-tile triangle is not tested here: its bounds already say it touches the tile.
      if (!singleTile && classifyTile(edges, bounds, tx, ty, format) == TileCoverage::Outside) {
        ++stats.tilesTriviallyRejected;
        continue;
      }
      entries_.push_back({uint32_t(ty * tilesX_ + tx), triangle});
    }
  }
}

void TileBins::finish() {
  offsets_.assign(size_t(tileCount()) + 1, 0);
  for (const Entry& e : entries_) ++offsets_[e.tile + 1];
  for (int t = 0; t < tileCount(); ++t) offsets_[t + 1] += offsets_[t];
  triangles_.resize(entries_.size());
  std::vector<uint32_t> cursor(offsets_.begin(), offsets_.end() - 1);
  for (const Entry& e : entries_) triangles_[cursor[e.tile]++] = e.triangle;
}

}  // namespace rast
