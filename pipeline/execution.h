// How a draw runs: threads, coverage kernel, back-end target and binning levels. No choice changes
// an output bit: tiles are owned by one task at a time and triangles merge in submission order.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "pipeline/scratch_memory.h"
#include "rasterizer/coverage_kernels.h"

namespace rast {

struct StageTimings;
struct DrawCapture;

// The instruction set the back end's tile loop runs in. One source is compiled for both (every
// helper inlined into each), so the choice changes no bit, only the speed.
enum class BackEndTarget {
  Auto,      // AVX2 (with BMI1/2, LZCNT, POPCNT) where the CPU has it, else the baseline
  Baseline,  // the x86-64 baseline (SSE2) build
};

// How binning places large triangles (bin.h): per 64x64-pixel coarse tile first, or tile by tile
// (one level, for study). Either gives every tile the same entries.
enum class BinLevels { Coarse, TilesOnly };

struct ExecutionOptions {
  int threads = 0;  // worker threads for a draw; 0: every hardware thread
  CoverageKernel coverage = bestCoverageKernel();
  BackEndTarget backEnd = BackEndTarget::Auto;
  BinLevels binLevels = BinLevels::Coarse;
  // Hidden-surface removal before shading (tile_loop.h): where a pixel keeps its last passing
  // fragment's colour, a tile shades only the fragments it keeps. Off, every passing fragment is
  // shaded as it passes; the output and the statistics are the same either way.
  bool deferShading = true;
  // Memory kept between draws (scratch_memory.h); null: each draw allocates its own. The same
  // object may serve any number of draws, one after another or at once.
  ScratchMemory* memory = nullptr;
  // Optional instrumentation (pipeline/instrumentation.h), filled when not null.
  StageTimings* timings = nullptr;
  DrawCapture* capture = nullptr;
};

// Per-draw temporaries: from `memory` when the draw was given one (ExecutionOptions::memory,
// scratch_memory.h), which keeps large blocks for the next draw, else from oneTBB's scalable
// allocator. Growing one default-initialises its elements: every user writes each element before
// reading it, so zeroing them first would be a wasted pass.
template <class T>
struct ScratchAllocator {
  using value_type = T;
  using propagate_on_container_copy_assignment = std::true_type;
  using propagate_on_container_move_assignment = std::true_type;
  using propagate_on_container_swap = std::true_type;

  ScratchMemory* memory = nullptr;

  ScratchAllocator() = default;
  explicit ScratchAllocator(ScratchMemory* m) noexcept : memory(m) {}
  template <class U>
  ScratchAllocator(const ScratchAllocator<U>& other) noexcept : memory(other.memory) {}

  T* allocate(size_t n) { return static_cast<T*>(scratchAllocate(memory, n * sizeof(T))); }
  void deallocate(T* p, size_t n) noexcept { scratchDeallocate(memory, p, n * sizeof(T)); }

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const ScratchAllocator<U>& other) const noexcept {
    return memory == other.memory;
  }
};

template <class T>
using ScratchVector = std::vector<T, ScratchAllocator<T>>;

// Calls f(chunk, begin, end) for consecutive chunks of [0, count) of `chunkSize` items, in
// parallel. Chunk boundaries depend only on count and chunkSize, never on the thread count.
template <class F>
void forEachChunk(size_t count, size_t chunkSize, F&& f) {
  const size_t chunks = (count + chunkSize - 1) / chunkSize;
  tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
    f(c, c * chunkSize, std::min(count, (c + 1) * chunkSize));
  });
}

inline size_t chunkCount(size_t count, size_t chunkSize) {
  return (count + chunkSize - 1) / chunkSize;
}

}  // namespace rast
