#include "debug/debug_images.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>

#include "debug/color_scale.h"
#include "shaders_cpp/triangle_id.h"

namespace rast {
namespace {

constexpr Rgb kNothing{40, 40, 40};

std::string integer(uint64_t v) { return std::to_string(v); }

std::string decimal(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// Counts 0 dark, 1..max along the colour scale.
Rgb countColor(uint32_t v, uint32_t max) {
  if (v == 0) return kNothing;
  return viridis(max > 1 ? double(v - 1) / double(max - 1) : 1.0);
}

RgbImage countImage(const std::vector<uint32_t>& counts, int width, int height, int cell) {
  const uint32_t max = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
  RgbImage img(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      img.at(x, y) = countColor(counts[size_t(y / cell) * size_t((width + cell - 1) / cell) + size_t(x / cell)], max);
  const int factor = enlargementFor(width, height);
  return withLegend(enlarge(img, factor), {integer(std::min<uint32_t>(1, std::max<uint32_t>(max, 1))),
                                           integer(std::max<uint32_t>(max, 1)), true, kNothing, "0"});
}

// Every draw's state with depth "always" and no writes: the pass records only coverage.
PipelineState coverageOnly(PipelineState s, bool cull) {
  s.depth.compare = CompareOp::Always;
  s.depth.write = false;
  s.colorWrite = false;
  if (!cull) s.cullMode = CullMode::None;
  return s;
}

Status coveragePass(const FramePlan& plan, bool cull, const ExecutionOptions& exec,
                    std::vector<uint32_t>& counts) {
  Framebuffer fb(plan.width, plan.height, true);
  fb.clear(plan.background, plan.clearDepth);
  for (const FrameDraw& d : plan.draws) {
    PipelineStatistics ignored;
    if (Status s = d.run(fb, coverageOnly(d.state, cull), PixelPass::Scene, 0, ignored, exec); !s)
      return s;
  }
  counts = fb.countPlane();
  return Status::ok();
}

}  // namespace

Status captureDebugData(const FramePlan& plan, std::optional<std::pair<int, int>> tile,
                        const ExecutionOptions& exec, DebugData& out) {
  DebugData d;
  d.width = plan.width;
  d.height = plan.height;
  d.tilesX = (plan.width + kTileSize - 1) / kTileSize;
  d.tilesY = (plan.height + kTileSize - 1) / kTileSize;
  d.binEntries.assign(size_t(d.tilesX) * size_t(d.tilesY), 0);

  // 1. The frame as planned.
  Framebuffer fb(plan.width, plan.height, true);
  fb.clear(plan.background, plan.clearDepth);
  for (const FrameDraw& draw : plan.draws) {
    DrawCapture capture;
    ExecutionOptions e = exec;
    e.capture = &capture;
    PipelineStatistics ignored;
    if (Status s = draw.run(fb, draw.state, PixelPass::Scene, 0, ignored, e); !s) return s;
    for (size_t t = 0; t < capture.binEntries.size(); ++t) d.binEntries[t] += capture.binEntries[t];
  }
  d.overdraw = fb.countPlane();
  d.depth = fb.depthPlane();

  if (tile) {
    if (tile->first < 0 || tile->first >= d.tilesX || tile->second < 0 || tile->second >= d.tilesY)
      return Status::error("tile " + std::to_string(tile->first) + "," + std::to_string(tile->second) +
                           " is outside the " + std::to_string(d.tilesX) + "x" +
                           std::to_string(d.tilesY) + " tiles of the frame");
    d.zoomTileX = tile->first;
    d.zoomTileY = tile->second;
  } else {
    const size_t busiest = size_t(std::max_element(d.binEntries.begin(), d.binEntries.end()) -
                                  d.binEntries.begin());
    d.zoomTileX = int(busiest % size_t(d.tilesX));
    d.zoomTileY = int(busiest / size_t(d.tilesX));
  }

  // 2. Triangle ids, and the triangles of the zoomed tile (setup does not depend on the shader).
  fb.clear(glm::vec4(0, 0, 0, 1), plan.clearDepth);
  uint64_t idBase = 0;
  for (size_t i = 0; i < plan.draws.size(); ++i) {
    const FrameDraw& draw = plan.draws[i];
    DrawCapture capture;
    capture.zoomTileX = d.zoomTileX;
    capture.zoomTileY = d.zoomTileY;
    ExecutionOptions e = exec;
    e.capture = &capture;
    PipelineStatistics ignored;
    if (Status s = draw.run(fb, draw.state, PixelPass::TriangleId, uint32_t(idBase), ignored, e); !s)
      return s;
    for (const CapturedTriangle& t : capture.zoomTriangles)
      d.zoomTriangles.push_back({i, draw.label, idBase + t.primitiveId, draw.state.format, t,
                                 coverageScalar(t.edges, t.bounds, d.zoomTileX, d.zoomTileY,
                                                draw.state.format)});
    idBase += draw.triangleCount;
  }
  d.triangleIds.resize(fb.colorPlane().size());
  for (size_t p = 0; p < d.triangleIds.size(); ++p)
    d.triangleIds[p] = TriangleIdShader::decode(fb.colorPlane()[p]);

  // 3 and 4. Coverage with the draws' culling, and without.
  std::vector<uint32_t> covered, coveredUnculled;
  if (Status s = coveragePass(plan, true, exec, covered); !s) return s;
  if (Status s = coveragePass(plan, false, exec, coveredUnculled); !s) return s;
  d.stages.resize(d.overdraw.size());
  for (size_t p = 0; p < d.stages.size(); ++p)
    d.stages[p] = d.overdraw[p] > 0      ? PixelStage::Shaded
                  : covered[p] > 0       ? PixelStage::FailedDepth
                  : coveredUnculled[p] > 0 ? PixelStage::Culled
                                           : PixelStage::NotCovered;
  out = std::move(d);
  return Status::ok();
}

RgbImage binHeatMapImage(const DebugData& d) {
  return countImage(d.binEntries, d.width, d.height, kTileSize);
}

RgbImage overdrawImage(const DebugData& d) { return countImage(d.overdraw, d.width, d.height, 1); }

RgbImage triangleIdImage(const DebugData& d) {
  RgbImage img(d.width, d.height);
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x) {
      const int64_t id = d.triangleIds[size_t(y) * size_t(d.width) + size_t(x)];
      img.at(x, y) = id < 0 ? Rgb{0, 0, 0} : idColor(uint64_t(id));
    }
  return enlarge(img, enlargementFor(d.width, d.height));
}

RgbImage depthImage(const DebugData& d) {
  // Only pixels something was written to: the clear value would flatten the scale.
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (size_t p = 0; p < d.depth.size(); ++p)
    if (d.overdraw[p] > 0 && std::isfinite(d.depth[p])) {
      lo = std::min(lo, d.depth[p]);
      hi = std::max(hi, d.depth[p]);
    }
  const bool any = lo <= hi;
  RgbImage img(d.width, d.height);
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x) {
      const size_t p = size_t(y) * size_t(d.width) + size_t(x);
      // Near is bright: the scale runs from yellow (near) to purple (far).
      img.at(x, y) = d.overdraw[p] == 0 || !std::isfinite(d.depth[p])
                         ? kNothing
                         : viridis(hi > lo ? 1.0 - (double(d.depth[p]) - lo) / (double(hi) - lo) : 1.0);
    }
  // The legend runs from far (left, dark) to near (right, bright).
  return withLegend(enlarge(img, enlargementFor(d.width, d.height)),
                    {any ? decimal(hi) : "1", any ? decimal(lo) : "0", false, {}, ""});
}

Rgb stageColor(PixelStage stage) {
  switch (stage) {
    case PixelStage::NotCovered: return kNothing;
    case PixelStage::Culled: return {150, 90, 210};
    case PixelStage::FailedDepth: return {225, 85, 60};
    case PixelStage::Shaded: return {90, 200, 110};
  }
  return kNothing;
}

RgbImage stageImage(const DebugData& d) {
  RgbImage img(d.width, d.height);
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x)
      img.at(x, y) = stageColor(d.stages[size_t(y) * size_t(d.width) + size_t(x)]);
  return enlarge(img, enlargementFor(d.width, d.height));
}

Rgb zoomColor(size_t i) {
  static constexpr Rgb kPalette[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},
                                     {214, 39, 40},  {148, 103, 189}, {140, 86, 75},
                                     {227, 119, 194}, {188, 189, 34}, {23, 190, 207}};
  return kPalette[i % std::size(kPalette)];
}

RgbImage tileZoomImage(const DebugData& d) {
  constexpr int kCell = 48, kMargin = 16, kSide = kTileSize * kCell + 2 * kMargin;
  RgbImage img(kSide, kSide, {250, 250, 250});
  auto tint = [](Rgb c) {
    return Rgb{uint8_t((c.r + 2 * 255) / 3), uint8_t((c.g + 2 * 255) / 3), uint8_t((c.b + 2 * 255) / 3)};
  };
  // Pixel cells: each covering triangle's colour as a vertical band, in submission order.
  for (int cy = 0; cy < kTileSize; ++cy)
    for (int cx = 0; cx < kTileSize; ++cx) {
      const int x0 = kMargin + cx * kCell, y0 = kMargin + cy * kCell;
      const CoverageMask bit = CoverageMask{1} << coverageBit(cx, cy);
      std::vector<size_t> covering;
      for (size_t i = 0; i < d.zoomTriangles.size(); ++i)
        if (d.zoomTriangles[i].mask & bit) covering.push_back(i);
      const bool outside = d.zoomTileX * kTileSize + cx >= d.width || d.zoomTileY * kTileSize + cy >= d.height;
      img.fillRect(x0, y0, x0 + kCell, y0 + kCell, outside ? Rgb{200, 200, 200} : Rgb{235, 235, 235});
      for (size_t k = 0; k < covering.size(); ++k)
        img.fillRect(x0 + int(k * kCell / covering.size()), y0,
                     x0 + int((k + 1) * kCell / covering.size()), y0 + kCell,
                     tint(zoomColor(covering[k])));
    }
  // The pixel grid.
  for (int i = 0; i <= kTileSize; ++i) {
    const int p = kMargin + i * kCell;
    img.fillRect(p, kMargin, p + 1, kSide - kMargin + 1, {160, 160, 160});
    img.fillRect(kMargin, p, kSide - kMargin + 1, p + 1, {160, 160, 160});
  }
  // The snapped edges: where the edge function (without its fill-rule bias) is within a zoomed
  // pixel of zero and the other two are not far negative, i.e. the segment between the vertices.
  for (size_t i = 0; i < d.zoomTriangles.size(); ++i) {
    const ZoomTriangle& z = d.zoomTriangles[i];
    const double unit = std::ldexp(1.0, z.format.fractionBits);  // subpixels per pixel
    const int64_t originX = int64_t(d.zoomTileX) * kTileSize << z.format.fractionBits;
    const int64_t originY = int64_t(d.zoomTileY) * kTileSize << z.format.fractionBits;
    std::array<double, 3> atOrigin, length;
    for (int e = 0; e < 3; ++e) {
      const EdgeFunction& f = z.triangle.edges[size_t(e)];
      const int64_t bias = EdgeFunction::isTopLeft(f.a, f.b) ? 0 : 1;
      atOrigin[size_t(e)] = double(f.at(originX, originY) + bias);
      length[size_t(e)] = std::hypot(double(f.a), double(f.b));
    }
    const double halfWidth = 1.2 * unit / kCell;  // subpixels
    const Rgb dark{uint8_t(zoomColor(i).r * 2 / 3), uint8_t(zoomColor(i).g * 2 / 3), uint8_t(zoomColor(i).b * 2 / 3)};
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        const double dx = (x - kMargin + 0.5) / kCell * unit, dy = (y - kMargin + 0.5) / kCell * unit;
        std::array<double, 3> distance;
        for (int e = 0; e < 3; ++e) {
          const EdgeFunction& f = z.triangle.edges[size_t(e)];
          distance[size_t(e)] = (atOrigin[size_t(e)] + double(f.a) * dx + double(f.b) * dy) / length[size_t(e)];
        }
        for (int e = 0; e < 3; ++e)
          if (std::abs(distance[size_t(e)]) <= halfWidth && distance[size_t((e + 1) % 3)] >= -halfWidth &&
              distance[size_t((e + 2) % 3)] >= -halfWidth)
            img.at(x, y) = dark;
      }
  }
  // Sample points: filled when covered by any triangle, hollow when not.
  for (int cy = 0; cy < kTileSize; ++cy)
    for (int cx = 0; cx < kTileSize; ++cx) {
      const CoverageMask bit = CoverageMask{1} << coverageBit(cx, cy);
      bool covered = false;
      for (const ZoomTriangle& z : d.zoomTriangles) covered |= (z.mask & bit) != 0;
      const int sx = kMargin + cx * kCell + kCell / 2, sy = kMargin + cy * kCell + kCell / 2;
      img.fillRect(sx - 4, sy - 4, sx + 4, sy + 4, {20, 20, 20});
      if (!covered) img.fillRect(sx - 2, sy - 2, sx + 2, sy + 2, {250, 250, 250});
    }
  return img;
}

std::vector<DebugImage> debugImages(const DebugData& d) {
  const std::string tile = std::to_string(d.zoomTileX) + "," + std::to_string(d.zoomTileY);
  return {
      {"bin_heatmap", "Bin heat map",
       "Triangles binned to each 8x8 tile (bin entries), all draws; dark: none.", binHeatMapImage(d)},
      {"overdraw", "Overdraw", "Fragments written per pixel; dark: none.", overdrawImage(d)},
      {"triangle_id", "Triangle id",
       "The triangle that wrote each pixel last, one colour per triangle (ids count across draws).",
       triangleIdImage(d)},
      {"depth", "Depth",
       "Depth of the written pixels, far (dark, left of the scale) to near (bright, right); "
       "dark grey: nothing written.",
       depthImage(d)},
      {"stage", "Which stage decided each pixel",
       "Green: shaded; red: covered but failed depth (or discarded); purple: covered only by culled "
       "triangles; dark grey: not covered.",
       stageImage(d)},
      {"tile_" + std::to_string(d.zoomTileX) + "_" + std::to_string(d.zoomTileY),
       "Coverage of tile " + tile,
       "Pixel grid of tile " + tile + " with its sample points (filled: covered), each triangle's "
       "covered samples in its colour (bands in submission order) and its snapped edges as lines.",
       tileZoomImage(d)},
  };
}

}  // namespace rast
