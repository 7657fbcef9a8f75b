// Visual debugging of a frame: what binning, coverage, depth and shading did, pixel by pixel.
// Everything is measured by running the frame's draws through the real pipeline, several times:
//   1. as planned, counting written fragments and capturing the per-tile bin entries;
//   2. with a triangle-id shader, capturing the triangles binned to the zoomed tile;
//   3. with depth compare "always", no depth or colour writes: what the draws cover;
//   4. the same with culling off: what they would cover unculled.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "debug/rgb_image.h"
#include "pipeline/instrumentation.h"
#include "rasterizer/coverage.h"
#include "scene/frame.h"

namespace rast {

// Which stage decided a pixel's final value, from the passes above.
enum class PixelStage : uint8_t {
  NotCovered,   // no triangle covers it, even unculled
  Culled,       // covered only by culled triangles
  FailedDepth,  // covered, but no fragment was written (failed depth, or discarded)
  Shaded,       // a fragment was written
};

// A triangle binned to the zoomed tile.
struct ZoomTriangle {
  size_t draw = 0;
  std::string label;        // the draw's
  uint64_t triangleId = 0;  // frame-wide: earlier draws' triangles + primitive id
  FixedPointFormat format;
  CapturedTriangle triangle;
  CoverageMask mask = 0;  // its covered samples in the tile
};

struct DebugData {
  int width = 0, height = 0;
  int tilesX = 0, tilesY = 0;
  std::vector<uint32_t> binEntries;   // per tile: (triangle, tile) pairs over every draw
  std::vector<uint32_t> overdraw;     // per pixel: fragments written
  std::vector<int64_t> triangleIds;   // per pixel: frame-wide id of the last written, or -1
  std::vector<float> depth;           // the depth buffer after the frame
  std::vector<PixelStage> stages;
  int zoomTileX = 0, zoomTileY = 0;
  std::vector<ZoomTriangle> zoomTriangles;  // in the order the tile ran them
};

// `tile`: the tile to zoom into; by default the one with the most bin entries.
Status captureDebugData(const FramePlan& plan, std::optional<std::pair<int, int>> tile,
                        const ExecutionOptions& exec, DebugData& out);

struct DebugImage {
  std::string name;     // file stem, e.g. "bin_heatmap"
  std::string title;
  std::string caption;  // what the colours mean
  RgbImage image;
};

RgbImage binHeatMapImage(const DebugData& d);
RgbImage overdrawImage(const DebugData& d);
RgbImage triangleIdImage(const DebugData& d);
RgbImage depthImage(const DebugData& d);
RgbImage stageImage(const DebugData& d);
RgbImage tileZoomImage(const DebugData& d);
// The colours stageImage uses.
Rgb stageColor(PixelStage stage);
Rgb zoomColor(size_t indexInTile);

// All of the above with titles and captions.
std::vector<DebugImage> debugImages(const DebugData& d);

}  // namespace rast
