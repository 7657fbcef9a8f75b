// How a draw runs: how many threads and which coverage kernel. Neither changes any output bit:
// tiles are owned by one task at a time and triangles merge in submission order.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/scalable_allocator.h>

#include "rasterizer/coverage_kernels.h"

namespace rast {

struct StageTimings;
struct DrawCapture;

struct ExecutionOptions {
  int threads = 0;  // worker threads for a draw; 0: every hardware thread
  CoverageKernel coverage = bestCoverageKernel();
  // Optional instrumentation (pipeline/instrumentation.h), filled when not null.
  StageTimings* timings = nullptr;
  DrawCapture* capture = nullptr;
};

// Per-draw temporaries, from oneTBB's scalable allocator. (It does not keep every large block
// for the next draw: a warm W2 tiny-1 frame still page-faults through ~130 MB; a persistent
// per-context arena is the fix.) Growing one default-initialises its elements: every user
// writes each element before reading it, so zeroing them first would be a wasted pass.
template <class T>
struct ScratchAllocator : tbb::scalable_allocator<T> {
  template <class U>
  struct rebind {
    using other = ScratchAllocator<U>;
  };
  ScratchAllocator() = default;
  template <class U>
  ScratchAllocator(const ScratchAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
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
