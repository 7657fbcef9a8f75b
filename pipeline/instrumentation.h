// Optional outputs of a draw for people studying it: wall time per stage, and a capture of what
// binning produced. Kept out of PipelineStatistics, which is exact and thread-count independent;
// timings are neither. A draw fills these only when ExecutionOptions points to them.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/bin.h"
#include "pipeline/setup.h"
#include "rasterizer/edge_function.h"
#include "rasterizer/pixel_rect.h"

namespace rast {

// Seconds spent in each stage of the draws it was given to, summed.
struct StageTimings {
  double vertex = 0;
  // Draws of a few chunks of triangles per thread bin each chunk in the task that set it up
  // (binWhileSettingUp, draw.h): there clipSetup includes that binning and bin is the sort of
  // the bins alone. Other draws (few, large triangles) bin in a pass of their own, all in bin.
  double clipSetup = 0;
  double bin = 0;
  double backEnd = 0;  // raster, depth, interpolation, pixel shader and merge, per tile
  // How many of the draws binned while setting up, so a table can say what clipSetup holds.
  uint64_t drawsBinnedInSetup = 0;

  double total() const { return vertex + clipSetup + bin + backEnd; }
  StageTimings& operator+=(const StageTimings& o) {
    vertex += o.vertex;
    clipSetup += o.clipSetup;
    bin += o.bin;
    backEnd += o.backEnd;
    drawsBinnedInSetup += o.drawsBinnedInSetup;
    return *this;
  }
};

// Every stage with its name: the one list that tables and JSON use.
inline constexpr std::array<std::pair<const char*, double StageTimings::*>, 4> kStageTimings = {{
    {"vertex", &StageTimings::vertex},
    {"clip_setup", &StageTimings::clipSetup},
    {"bin", &StageTimings::bin},
    {"back_end", &StageTimings::backEnd},
}};

// Adds the time since the previous lap to a stage; reads no clock when there is nowhere to add it.
class StageClock {
 public:
  explicit StageClock(StageTimings* timings) : timings_(timings) {
    if (timings_) last_ = std::chrono::steady_clock::now();
  }
  void lap(double StageTimings::*stage) {
    if (!timings_) return;
    const auto now = std::chrono::steady_clock::now();
    timings_->*stage += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

 private:
  StageTimings* timings_;
  std::chrono::steady_clock::time_point last_;
};

// A set-up triangle as the coverage stage sees it.
struct CapturedTriangle {
  std::array<EdgeFunction, 3> edges;
  PixelRect bounds;
  uint32_t primitiveId = 0;
};

// What binning produced, added up over the draws it is given to (all on one framebuffer size).
struct DrawCapture {
  int tilesX = 0, tilesY = 0;
  std::vector<uint32_t> binEntries;  // per tile (row-major): (triangle, tile) pairs
  // The tile whose triangles are kept (-1: none), and those triangles, in the order it ran them.
  int zoomTileX = -1, zoomTileY = -1;
  std::vector<CapturedTriangle> zoomTriangles;

  // `triangles[id]`: the set-up triangle a bin entry names (SetupTriangles in front_end.h).
  template <class Triangles>
  void record(const TileBins& bins, const Triangles& triangles) {
    tilesX = bins.tilesX();
    tilesY = bins.tilesY();
    binEntries.resize(size_t(bins.tileCount()), 0);
    std::vector<uint32_t> scratch;
    for (int t = 0; t < bins.tileCount(); ++t)
      binEntries[size_t(t)] += uint32_t(bins.entries(t, scratch).size());
    if (zoomTileX < 0 || zoomTileX >= tilesX || zoomTileY < 0 || zoomTileY >= tilesY) return;
    for (const uint32_t entry : bins.entries(zoomTileY * tilesX + zoomTileX, scratch)) {
      const auto& t = triangles[entry & ~kWholeTileBit];
      zoomTriangles.push_back({t.edges, t.bounds, t.primitiveId()});
    }
  }
};

}  // namespace rast
