#include "pipeline/scratch_memory.h"

#include <bit>
#include <new>

#include <tbb/scalable_allocator.h>

namespace rast {
namespace {

// Sizes rounded up to 8 classes per power of two (at most 12.5 % over), so that blocks of a
// growing vector or of a scene that changes a little still meet a kept block of their class.
size_t sizeClass(size_t bytes) {
  const int shift = std::bit_width(bytes) - 4;  // bytes >= kMinKept, so shift > 0
  const size_t unit = size_t{1} << shift;
  return (bytes + unit - 1) & ~(unit - 1);
}

void* fresh(size_t bytes) {
  void* p = scalable_aligned_malloc(bytes, 64);
  if (!p) throw std::bad_alloc();
  return p;
}

}  // namespace

void* ScratchMemory::allocate(size_t bytes) {
  if (bytes < kMinKept) return fresh(bytes);
  const size_t size = sizeClass(bytes);
  {
    std::lock_guard lock(mutex_);
    if (auto it = kept_.find(size); it != kept_.end()) {
      void* p = it->second;
      kept_.erase(it);
      keptBytes_ -= size;
      return p;
    }
  }
  return fresh(size);
}

void ScratchMemory::deallocate(void* p, size_t bytes) {
  if (!p) return;
  if (bytes < kMinKept) {
    scalable_aligned_free(p);
    return;
  }
  const size_t size = sizeClass(bytes);
  std::lock_guard lock(mutex_);
  try {
    kept_.emplace(size, p);
    keptBytes_ += size;
  } catch (const std::bad_alloc&) {
    scalable_aligned_free(p);  // no room to remember it: give it back instead
  }
}

size_t ScratchMemory::release() {
  std::lock_guard lock(mutex_);
  for (const auto& [size, p] : kept_) scalable_aligned_free(p);
  kept_.clear();
  const size_t freed = keptBytes_;
  keptBytes_ = 0;
  return freed;
}

size_t ScratchMemory::keptBytes() const {
  std::lock_guard lock(mutex_);
  return keptBytes_;
}

void* scratchAllocate(ScratchMemory* memory, size_t bytes) {
  return memory ? memory->allocate(bytes) : fresh(bytes);
}

void scratchDeallocate(ScratchMemory* memory, void* p, size_t bytes) {
  if (memory) memory->deallocate(p, bytes);
  else scalable_aligned_free(p);
}

}  // namespace rast
