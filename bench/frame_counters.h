// The counters every frame benchmark reports, ours and the peer's alike, so that their columns
// line up and the fragment counts can be checked against ../shared/design/workloads.md.
#pragma once

#include <cstdint>

#include <benchmark/benchmark.h>

namespace rast::bench {

// Per-frame counts; each rate divides count x iterations by the (real) time.
struct FrameCounts {
  uint64_t triangles = 0;    // submitted
  uint64_t rasterized = 0;   // fragments (covered samples)
  uint64_t depthPassed = 0;  // fragments that passed the depth test
  uint64_t shaded = 0;       // pixel shader invocations
};

inline void reportFrameCounts(benchmark::State& state, const FrameCounts& frame) {
  using benchmark::Counter;
  state.counters["triangles/s"] = Counter(double(frame.triangles), Counter::kIsIterationInvariantRate);
  state.counters["shaded_px/s"] = Counter(double(frame.shaded), Counter::kIsIterationInvariantRate);
  state.counters["triangles"] = double(frame.triangles);
  state.counters["rasterized"] = double(frame.rasterized);
  state.counters["depth_passed"] = double(frame.depthPassed);
}

}  // namespace rast::bench
