// Blending and the colour write mask, as the output merger applies them to one pixel: the
// shader's colour (src) and the stored colour (dst, unpacked from RGBA8 by unpackColor) combine
// as  result = op(src * srcFactor, dst * dstFactor),  separately for RGB and alpha, and the
// result is packed again by packColor (which clamps to [0, 1]).
//
// Conventions of OpenGL and Direct3D 11 for a normalized (UNORM) target: src and the constant
// colour are clamped to [0, 1] first (a NaN channel becomes 0, as in packColor); Min and Max
// take the plain src and dst and ignore both factors. A factor applied to the alpha channel uses
// its alpha component (SrcColor on alpha is src.a, ConstantColor is constant.a).
#pragma once

#include <cstdint>

#include <glm/common.hpp>
#include <glm/vec4.hpp>

#include "pipeline/framebuffer.h"

namespace rast {

enum class BlendOp { Add, Subtract, ReverseSubtract, Min, Max };

enum class BlendFactor {
  Zero,
  One,
  SrcColor,
  OneMinusSrcColor,
  DstColor,
  OneMinusDstColor,
  SrcAlpha,
  OneMinusSrcAlpha,
  DstAlpha,
  OneMinusDstAlpha,
  ConstantColor,
  OneMinusConstantColor,
};

struct BlendState {
  bool enable = false;  // off: the result is src
  BlendOp colorOp = BlendOp::Add;
  BlendFactor srcColor = BlendFactor::One;
  BlendFactor dstColor = BlendFactor::Zero;
  BlendOp alphaOp = BlendOp::Add;
  BlendFactor srcAlpha = BlendFactor::One;
  BlendFactor dstAlpha = BlendFactor::Zero;
  glm::vec4 constant{0.0f};

  friend bool operator==(const BlendState&, const BlendState&) = default;

  // Classic "over" with straight alpha: src * a + dst * (1 - a); alpha likewise.
  static BlendState alphaBlend() {
    return {true,          BlendOp::Add, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha,
            BlendOp::Add, BlendFactor::One, BlendFactor::OneMinusSrcAlpha, glm::vec4(0.0f)};
  }
  // Additive light: src + dst, alpha likewise.
  static BlendState additive() {
    return {true,          BlendOp::Add, BlendFactor::One, BlendFactor::One,
            BlendOp::Add, BlendFactor::One, BlendFactor::One, glm::vec4(0.0f)};
  }
};

// Channels the merge may change; the others keep the stored value.
enum ColorWriteMask : uint8_t {
  kWriteNone = 0,
  kWriteRed = 1,
  kWriteGreen = 2,
  kWriteBlue = 4,
  kWriteAlpha = 8,
  kWriteAll = 15,
};

namespace detail {

inline float saturate(float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; }
inline glm::vec4 saturate(glm::vec4 c) {
  return {saturate(c.r), saturate(c.g), saturate(c.b), saturate(c.a)};
}

inline glm::vec4 blendFactor(BlendFactor f, glm::vec4 src, glm::vec4 dst, glm::vec4 constant) {
  switch (f) {
    case BlendFactor::Zero: return glm::vec4(0.0f);
    case BlendFactor::One: return glm::vec4(1.0f);
    case BlendFactor::SrcColor: return src;
    case BlendFactor::OneMinusSrcColor: return 1.0f - src;
    case BlendFactor::DstColor: return dst;
    case BlendFactor::OneMinusDstColor: return 1.0f - dst;
    case BlendFactor::SrcAlpha: return glm::vec4(src.a);
    case BlendFactor::OneMinusSrcAlpha: return glm::vec4(1.0f - src.a);
    case BlendFactor::DstAlpha: return glm::vec4(dst.a);
    case BlendFactor::OneMinusDstAlpha: return glm::vec4(1.0f - dst.a);
    case BlendFactor::ConstantColor: return constant;
    case BlendFactor::OneMinusConstantColor: return 1.0f - constant;
  }
  return glm::vec4(0.0f);
}

inline glm::vec4 blendOp(BlendOp op, glm::vec4 s, glm::vec4 d, glm::vec4 src, glm::vec4 dst) {
  switch (op) {
    case BlendOp::Add: return s + d;
    case BlendOp::Subtract: return s - d;
    case BlendOp::ReverseSubtract: return d - s;
    case BlendOp::Min: return glm::min(src, dst);
    case BlendOp::Max: return glm::max(src, dst);
  }
  return s;
}

}  // namespace detail

// The blended colour, before packing (it may leave [0, 1]: Add overflows, Subtract goes negative).
inline glm::vec4 blend(glm::vec4 src, glm::vec4 dst, const BlendState& state) {
  if (!state.enable) return src;
  src = detail::saturate(src);
  const glm::vec4 constant = detail::saturate(state.constant);
  const glm::vec4 s = src * detail::blendFactor(state.srcColor, src, dst, constant);
  const glm::vec4 d = dst * detail::blendFactor(state.dstColor, src, dst, constant);
  const glm::vec4 color = detail::blendOp(state.colorOp, s, d, src, dst);
  const float sa = src.a * detail::blendFactor(state.srcAlpha, src, dst, constant).a;
  const float da = dst.a * detail::blendFactor(state.dstAlpha, src, dst, constant).a;
  const float alpha = detail::blendOp(state.alphaOp, glm::vec4(sa), glm::vec4(da), glm::vec4(src.a),
                                      glm::vec4(dst.a)).a;
  return {color.r, color.g, color.b, alpha};
}

// The stored pixel with the channels in `mask` replaced by `written`'s.
inline PackedColor applyWriteMask(PackedColor written, PackedColor stored, uint8_t mask) {
  uint32_t bytes = 0;
  for (int c = 0; c < 4; ++c)
    if (mask & (1u << c)) bytes |= 0xFFu << (8 * c);
  return (written & bytes) | (stored & ~bytes);
}

// What the merge writes for one pixel: blend with the stored RGBA8 value, pack, apply the mask.
inline PackedColor blendAndPack(glm::vec4 src, PackedColor stored, const BlendState& state,
                                uint8_t mask = kWriteAll) {
  const glm::vec4 result = state.enable ? blend(src, unpackColor(stored), state) : src;
  return applyWriteMask(packColor(result), stored, mask);
}

}  // namespace rast
