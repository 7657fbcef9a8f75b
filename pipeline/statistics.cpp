#include "pipeline/statistics.h"

#include <nlohmann/json.hpp>

namespace rast {

PipelineStatistics& PipelineStatistics::operator+=(const PipelineStatistics& o) {
  for (const auto& [name, member] : kPipelineCounters) this->*member += o.*member;
  return *this;
}

std::string PipelineStatistics::toJson(int indent) const {
  nlohmann::ordered_json j;
  forEachCounter([&](const char* name, uint64_t value) { j[name] = value; });
  return j.dump(indent);
}

}  // namespace rast
