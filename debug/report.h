// A self-contained HTML report of a run: scene, state, statistics, timings, debugging images
// (embedded as data: URIs) and the precision laboratory's table when one is given. No server and
// no network. A small inline script records after loading how many images decoded and how many
// tables have every cell filled (data-images-loaded, data-tables-filled on <body>), which the
// browser test reads back.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "debug/debug_images.h"
#include "debug/statistics_table.h"

namespace rast {

struct ReportImage {
  std::string title, caption;
  RgbImage image;
};

struct ReportInput {
  std::string title;
  std::string commandLine;
  TableData scene;       // key, value
  TableData drawStates;  // a row per draw
  TableData statistics;
  TableData timings;
  std::vector<ReportImage> images;  // the render first, then the debugging images
  TableData tileTriangles;
  std::optional<TableData> precision;  // the precision laboratory's table
  std::string precisionSource;
};

// The whole page; fails only when an image cannot be encoded.
Status htmlReport(const ReportInput& input, std::string& html);

// A CSV file (comma-separated, double quotes around fields that hold commas or quotes; the first
// row names the columns) as a table. Errors name the file and line.
Status readCsvTable(const std::string& path, TableData& out);
Status parseCsvTable(const std::string& text, const std::string& name, TableData& out);

// The table of the triangles in the zoomed tile: draw, triangle id, colour, covered samples.
TableData tileTriangleTable(const DebugData& d);
// The state of every draw of a plan.
TableData drawStateTable(const FramePlan& plan);

}  // namespace rast
