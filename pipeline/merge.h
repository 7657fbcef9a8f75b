// The output merger's parts: the depth compare and the framebuffer planes the back end writes.
// Blending: blend.h.
#pragma once

#include <cstdint>

#include "pipeline/framebuffer.h"
#include "pipeline/state.h"

namespace rast {

// What each compare op means, one fragment at a time: the reference that the tile loop's SIMD
// depth test (depthTestLanes, tile_loop.h) must match on every lane (tests/merge_test.cpp).
template <CompareOp Op>
constexpr bool depthPasses(float fragment, float stored) {
  if constexpr (Op == CompareOp::Never) return false;
  else if constexpr (Op == CompareOp::Less) return fragment < stored;
  else if constexpr (Op == CompareOp::Equal) return fragment == stored;
  else if constexpr (Op == CompareOp::LessEqual) return fragment <= stored;
  else if constexpr (Op == CompareOp::Greater) return fragment > stored;
  else if constexpr (Op == CompareOp::NotEqual) return fragment != stored;
  else if constexpr (Op == CompareOp::GreaterEqual) return fragment >= stored;
  else return true;
}

// Raw pointers into the framebuffer's planes, taken once per draw.
struct MergeTarget {
  PackedColor* color;
  float* depth;
  uint32_t* counts;  // null when not counting (an instrumentation output, not pipeline state)
};

}  // namespace rast
