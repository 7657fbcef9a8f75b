// Binning: each set-up triangle into the 8x8-pixel tiles it can touch, in submission order.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/statistics.h"
#include "rasterizer/coverage.h"

namespace rast {

// Triangle indices grouped by tile (a counting sort of (tile, triangle) pairs, stable, so each
// bin keeps submission order).
class TileBins {
 public:
  TileBins(int widthPixels, int heightPixels);

  int tilesX() const { return tilesX_; }
  int tilesY() const { return tilesY_; }
  int tileCount() const { return tilesX_ * tilesY_; }

  // Adds the triangle to every tile of its bounds that the corner test does not reject.
  void add(uint32_t triangle, const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
           FixedPointFormat format, PipelineStatistics& stats);
  // Groups what was added by tile; call once, after the last add.
  void finish();

  size_t entryCount() const { return entries_.size(); }
  std::span<const uint32_t> bin(int tile) const {
    return {triangles_.data() + offsets_[tile], triangles_.data() + offsets_[tile + 1]};
  }

 private:
  struct Entry {
    uint32_t tile;
    uint32_t triangle;
  };
  int tilesX_, tilesY_;
  std::vector<Entry> entries_;
  std::vector<uint32_t> offsets_;
  std::vector<uint32_t> triangles_;
};

}  // namespace rast
