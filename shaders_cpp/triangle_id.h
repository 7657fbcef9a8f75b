#pragma once

#include <cstdint>

#include "pipeline/framebuffer.h"
#include "pipeline/shader.h"

namespace rast {

// Writes primitiveId + 1 into the 24 colour bits (0 stays "no triangle"), exactly: each byte k is
// written as k / 255, which packs back to k.
struct TriangleIdShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = false;

  PixelResult operator()(const Fragment<0>& f) const {
    const uint32_t id = f.primitiveId + 1;
    return {glm::vec4(float(id & 255), float((id >> 8) & 255), float((id >> 16) & 255), 255.0f) /
            255.0f};
  }
  // The id a TriangleIdShader pixel holds, or -1 where none was drawn.
  static int64_t decode(PackedColor c) { return int64_t(c & 0xFFFFFF) - 1; }
};

}  // namespace rast
