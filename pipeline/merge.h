// The output merger: depth compare, depth write, colour write, fragment counting. Its
// configuration is a template parameter, fixed per draw, so the per-pixel code holds no branch on
// state (a disabled depth test reads no depth at all).
#pragma once

#include <cstdint>

#include "pipeline/framebuffer.h"
#include "pipeline/state.h"

namespace rast {

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

template <CompareOp Op, bool DepthWrite, bool ColorWrite, bool EarlyDepth,
          DepthFormat Format = DepthFormat::Float32>
struct MergeConfig {
  static constexpr CompareOp kCompare = Op;
  static constexpr DepthFormat kDepthFormat = Format;
  static constexpr bool kDepthWrite = DepthWrite;
  static constexpr bool kColorWrite = ColorWrite;
  static constexpr bool kEarlyDepth = EarlyDepth;
  static constexpr bool kDepthRead = Op != CompareOp::Always && Op != CompareOp::Never;
};

// Raw pointers into the framebuffer's planes, taken once per draw.
struct MergeTarget {
  PackedColor* color;
  float* depth;
  // Null when not counting. Counting is an instrumentation output, not pipeline state: one
  // perfectly predicted test per written fragment instead of a template parameter halves the
  // number of tile-loop instantiations (build time).
  uint32_t* counts;
};

}  // namespace rast
