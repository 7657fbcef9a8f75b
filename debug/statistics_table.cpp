#include "debug/statistics_table.h"

#include <algorithm>
#include <cstdio>

namespace rast {
namespace {

bool depthTestedEarly(const PipelineState& state, bool mayDiscard) {
  // As the tile loop decides: early when asked, and always when no pixel shader runs.
  const bool shades = state.colorWrite || mayDiscard;
  return state.depth.early || !shades;
}

std::string milliseconds(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", seconds * 1e3);
  return buffer;
}

DerivedCounters frameDerived(const FrameRecord& record) {
  DerivedCounters total;
  for (const DrawRecord& d : record.draws) total += deriveCounters(d.stats, d.state, d.mayDiscard);
  return total;
}

// Every counter row: name, then one value per draw and the frame's.
std::vector<std::pair<std::string, std::vector<uint64_t>>> counterRows(const FrameRecord& record) {
  std::vector<std::pair<std::string, std::vector<uint64_t>>> rows;
  for (const auto& [name, member] : kPipelineCounters) {
    std::vector<uint64_t> values;
    for (const DrawRecord& d : record.draws) values.push_back(d.stats.*member);
    values.push_back(record.total.*member);
    rows.emplace_back(name, std::move(values));
  }
  std::vector<std::vector<std::pair<const char*, uint64_t>>> derived;
  for (const DrawRecord& d : record.draws)
    derived.push_back(derivedCounterList(deriveCounters(d.stats, d.state, d.mayDiscard)));
  derived.push_back(derivedCounterList(frameDerived(record)));
  for (size_t k = 0; k < derived.back().size(); ++k) {
    std::vector<uint64_t> values;
    for (const auto& list : derived) values.push_back(list[k].second);
    rows.emplace_back(derived.back()[k].first, std::move(values));
  }
  return rows;
}

std::string totalColumnName(const FrameRecord& record) {
  return record.frames > 1 ? std::to_string(record.frames) + " frames" : "frame";
}

}  // namespace

DerivedCounters& DerivedCounters::operator+=(const DerivedCounters& o) {
  vertexCacheHits += o.vertexCacheHits;
  samplesTested += o.samplesTested;
  earlyDepthPassed += o.earlyDepthPassed;
  earlyDepthFailed += o.earlyDepthFailed;
  lateDepthPassed += o.lateDepthPassed;
  lateDepthFailed += o.lateDepthFailed;
  return *this;
}

DerivedCounters deriveCounters(const PipelineStatistics& s, const PipelineState& state, bool mayDiscard) {
  DerivedCounters d;
  d.vertexCacheHits = s.inputIndices - s.vertexShaderInvocations;
  d.samplesTested = s.tilesPartial * uint64_t(kTileSize * kTileSize);
  if (depthTestedEarly(state, mayDiscard)) {
    d.earlyDepthPassed = s.depthTestsPassed;
    d.earlyDepthFailed = s.depthTestsFailed;
  } else {
    d.lateDepthPassed = s.depthTestsPassed;
    d.lateDepthFailed = s.depthTestsFailed;
  }
  return d;
}

std::vector<std::pair<const char*, uint64_t>> derivedCounterList(const DerivedCounters& d) {
  return {{"vertex.cache_hits", d.vertexCacheHits},
          {"raster.samples_tested", d.samplesTested},
          {"merge.early_depth_passed", d.earlyDepthPassed},
          {"merge.early_depth_failed", d.earlyDepthFailed},
          {"merge.late_depth_passed", d.lateDepthPassed},
          {"merge.late_depth_failed", d.lateDepthFailed}};
}

TableData statisticsTableData(const FrameRecord& record, bool includeZeroRows) {
  TableData t;
  t.header.push_back("counter");
  for (const DrawRecord& d : record.draws) t.header.push_back(d.label);
  t.header.push_back(totalColumnName(record));
  for (const auto& [name, values] : counterRows(record)) {
    if (!includeZeroRows && std::all_of(values.begin(), values.end(), [](uint64_t v) { return v == 0; }))
      continue;
    std::vector<std::string> row{name};
    for (uint64_t v : values) row.push_back(std::to_string(v));
    t.rows.push_back(std::move(row));
  }
  return t;
}

TableData timingsTableData(const FrameRecord& record) {
  TableData t;
  t.header.push_back("stage (ms)");
  for (const DrawRecord& d : record.draws) t.header.push_back(d.label);
  t.header.push_back(totalColumnName(record));
  auto add = [&](const std::string& name, auto value) {
    std::vector<std::string> row{name};
    for (const DrawRecord& d : record.draws) row.push_back(milliseconds(value(d.timings)));
    row.push_back(milliseconds(value(record.timings)));
    t.rows.push_back(std::move(row));
  };
  for (const auto& [name, member] : kStageTimings)
    add(name, [member = member](const StageTimings& s) { return s.*member; });
  add("total", [](const StageTimings& s) { return s.total(); });
  return t;
}

std::string statisticsTable(const FrameRecord& record) {
  const TableData all = statisticsTableData(record, true);
  const TableData shown = statisticsTableData(record, false);
  const TableData times = timingsTableData(record);
  std::vector<size_t> widths(all.header.size(), 0);
  auto measure = [&](const std::vector<std::string>& row) {
    for (size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
  };
  measure(all.header);
  for (const auto& r : shown.rows) measure(r);
  for (const auto& r : times.rows) measure(r);
  measure(times.header);
  std::string out;
  auto line = [&](const std::vector<std::string>& row) {
    for (size_t i = 0; i < row.size(); ++i) {
      const std::string pad(widths[i] - row[i].size(), ' ');
      out += i == 0 ? row[i] + pad : "  " + pad + row[i];  // names left, numbers right
    }
    out += "\n";
  };
  auto rule = [&] {
    size_t total = 0;
    for (size_t w : widths) total += w + 2;
    out += std::string(total - 2, '-') + "\n";
  };
  line(all.header);
  rule();
  for (const auto& r : shown.rows) line(r);
  if (all.rows.size() > shown.rows.size())
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    out.append("(")
        .append(std::to_string(all.rows.size() - shown.rows.size()))
        .append(" counters are zero in every column and not shown)\n");
  out += "\n";
  line(times.header);
  rule();
  for (const auto& r : times.rows) line(r);
  if (const uint64_t n = record.timings.drawsBinnedInSetup; n > 0)
    out.append("(clip_setup includes binning in ")
        .append(std::to_string(n))
        .append(n == 1 ? " draw" : " draws")
        .append(", whose chunks were binned by the tasks that set them up; bin is then the sort)\n");
  return out;
}

nlohmann::ordered_json statisticsJson(const FrameRecord& record) {
  using Json = nlohmann::ordered_json;
  auto counters = [](const PipelineStatistics& s) {
    Json j = Json::object();
    s.forEachCounter([&](const char* name, uint64_t v) { j[name] = v; });
    return j;
  };
  auto derived = [](const DerivedCounters& d) {
    Json j = Json::object();
    for (const auto& [name, v] : derivedCounterList(d)) j[name] = v;
    return j;
  };
  auto timings = [](const StageTimings& t) {
    Json j = Json::object();
    for (const auto& [name, member] : kStageTimings) j[name] = t.*member * 1e3;
    j["total"] = t.total() * 1e3;
    return j;
  };
  Json j = counters(record.total);
  j["derived"] = derived(frameDerived(record));
  j["timings_ms"] = timings(record.timings);
  // Draws whose clip_setup time includes their binning (bin_ms is then the sort).
  j["draws_binned_in_setup"] = record.timings.drawsBinnedInSetup;
  j["frames"] = record.frames;
  j["draws"] = Json::array();
  for (const DrawRecord& d : record.draws)
    j["draws"].push_back({{"label", d.label},
                          {"counters", counters(d.stats)},
                          {"derived", derived(deriveCounters(d.stats, d.state, d.mayDiscard))},
                          {"timings_ms", timings(d.timings)},
                          {"binned_in_setup", d.timings.drawsBinnedInSetup > 0}});
  return j;
}

}  // namespace rast
