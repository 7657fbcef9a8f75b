// Memory kept from draw to draw. A draw's temporaries (transformed vertices, set-up triangles,
// bins) come to hundreds of megabytes on small-triangle scenes (W2 tiny-1: about 270 MB), and
// fresh pages cost a page fault each: on this machine a fifth of a tiny-1 frame went to faulting
// in memory that the previous frame had just given back. Blocks handed to a ScratchMemory are kept
// and handed out again to the next draw that asks for the same size class, as a GPU driver keeps
// its command and bin buffers.
#pragma once

#include <cstddef>
#include <map>
#include <mutex>

namespace rast {

class ScratchMemory {
 public:
  ScratchMemory() = default;
  ScratchMemory(const ScratchMemory&) = delete;
  ScratchMemory& operator=(const ScratchMemory&) = delete;
  ~ScratchMemory() { release(); }

  // Thread-safe. Blocks below kMinKept bytes go straight to oneTBB's allocator, which keeps
  // small blocks itself.
  void* allocate(size_t bytes);
  void deallocate(void* p, size_t bytes);

  // Frees the blocks kept for later draws; returns how many bytes that was.
  size_t release();
  size_t keptBytes() const;

  static constexpr size_t kMinKept = size_t{64} << 10;

 private:
  mutable std::mutex mutex_;
  std::multimap<size_t, void*> kept_;  // free blocks by size class
  size_t keptBytes_ = 0;
};

// Allocation through `memory` when given, else oneTBB's scalable allocator.
void* scratchAllocate(ScratchMemory* memory, size_t bytes);
void scratchDeallocate(ScratchMemory* memory, void* p, size_t bytes);

}  // namespace rast
