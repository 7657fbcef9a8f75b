// Pipeline statistics per draw and per frame, in the spirit of Direct3D's pipeline statistics
// queries: the counters of PipelineStatistics, a few derived from them and the draw's state, and
// the time per stage. As an aligned text table and as JSON.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/frame.h"

namespace rast {

// Counters that follow from the exact ones and the draw's state.
struct DerivedCounters {
  uint64_t vertexCacheHits = 0;   // indices read that reused a shaded vertex
  uint64_t samplesTested = 0;     // samples edge-tested one by one (64 per partial tile)
  uint64_t earlyDepthPassed = 0;  // depth tests before the pixel shader
  uint64_t earlyDepthFailed = 0;
  uint64_t lateDepthPassed = 0;   // depth tests after it
  uint64_t lateDepthFailed = 0;

  DerivedCounters& operator+=(const DerivedCounters& o);
};
DerivedCounters deriveCounters(const PipelineStatistics& stats, const PipelineState& state, bool mayDiscard);
std::vector<std::pair<const char*, uint64_t>> derivedCounterList(const DerivedCounters& d);

// One table: a row per counter, a column per draw and one for the frame (the sum). Rows that are
// zero in every column are left out, and a last line says how many. Times in milliseconds.
std::string statisticsTable(const FrameRecord& record);

// The frame's counters at the top level (as --stats always wrote them), then "derived",
// "timings_ms", "frames" and "draws" (each with "label", "counters", "derived", "timings_ms").
nlohmann::ordered_json statisticsJson(const FrameRecord& record);

// One row per stage and column per draw, for the report.
struct TableData {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};
TableData statisticsTableData(const FrameRecord& record, bool includeZeroRows);
TableData timingsTableData(const FrameRecord& record);

}  // namespace rast
