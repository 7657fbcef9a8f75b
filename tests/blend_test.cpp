// Blending and the colour write mask (pipeline/blend.h) on exactly representable values, so every
// result is exact: each operator's table, each factor on both sides, min/max ignoring factors,
// clamping of the source, and the RGBA8 path the merge takes.
#include <gtest/gtest.h>

#include <limits>

#include "pipeline/blend.h"

namespace rast {
namespace {

const glm::vec4 kSrc(0.5f, 0.25f, 0.75f, 0.5f);
const glm::vec4 kDst(0.25f, 0.5f, 0.125f, 0.75f);
const glm::vec4 kConstant(0.375f, 0.625f, 0.875f, 0.25f);

BlendState state(BlendOp op, BlendFactor src, BlendFactor dst) {
  return {true, op, src, dst, op, src, dst, kConstant};
}

TEST(Blend, OperatorTable) {
  struct Row {
    BlendOp op;
    glm::vec4 expected;  // factors One, One
  };
  const Row rows[] = {
      {BlendOp::Add, {0.75f, 0.75f, 0.875f, 1.25f}},
      {BlendOp::Subtract, {0.25f, -0.25f, 0.625f, -0.25f}},
      {BlendOp::ReverseSubtract, {-0.25f, 0.25f, -0.625f, 0.25f}},
      {BlendOp::Min, {0.25f, 0.25f, 0.125f, 0.5f}},
      {BlendOp::Max, {0.5f, 0.5f, 0.75f, 0.75f}},
  };
  for (const Row& r : rows)
    EXPECT_EQ(blend(kSrc, kDst, state(r.op, BlendFactor::One, BlendFactor::One)), r.expected)
        << int(r.op);
  // With factors src alpha (0.5) and one minus src alpha (0.5): the weighted operators change...
  const BlendFactor a = BlendFactor::SrcAlpha, ia = BlendFactor::OneMinusSrcAlpha;
  EXPECT_EQ(blend(kSrc, kDst, state(BlendOp::Add, a, ia)), glm::vec4(0.375f, 0.375f, 0.4375f, 0.625f));
  EXPECT_EQ(blend(kSrc, kDst, state(BlendOp::Subtract, a, ia)), glm::vec4(0.125f, -0.125f, 0.3125f, -0.125f));
  EXPECT_EQ(blend(kSrc, kDst, state(BlendOp::ReverseSubtract, a, ia)), glm::vec4(-0.125f, 0.125f, -0.3125f, 0.125f));
  // ...min and max do not: they ignore the factors, whatever they are (D3D11 and OpenGL).
  for (BlendFactor f : {BlendFactor::Zero, BlendFactor::SrcAlpha, BlendFactor::ConstantColor}) {
    EXPECT_EQ(blend(kSrc, kDst, state(BlendOp::Min, f, BlendFactor::Zero)), glm::vec4(0.25f, 0.25f, 0.125f, 0.5f));
    EXPECT_EQ(blend(kSrc, kDst, state(BlendOp::Max, BlendFactor::Zero, f)), glm::vec4(0.5f, 0.5f, 0.75f, 0.75f));
  }
}

TEST(Blend, EveryFactorOnBothSides) {
  struct Row {
    BlendFactor factor;
    glm::vec4 value;  // the factor as applied: RGB to colour, its alpha to alpha
  };
  const Row rows[] = {
      {BlendFactor::Zero, {0, 0, 0, 0}},
      {BlendFactor::One, {1, 1, 1, 1}},
      {BlendFactor::SrcColor, {0.5f, 0.25f, 0.75f, 0.5f}},
      {BlendFactor::OneMinusSrcColor, {0.5f, 0.75f, 0.25f, 0.5f}},
      {BlendFactor::DstColor, {0.25f, 0.5f, 0.125f, 0.75f}},
      {BlendFactor::OneMinusDstColor, {0.75f, 0.5f, 0.875f, 0.25f}},
      {BlendFactor::SrcAlpha, {0.5f, 0.5f, 0.5f, 0.5f}},
      {BlendFactor::OneMinusSrcAlpha, {0.5f, 0.5f, 0.5f, 0.5f}},
      {BlendFactor::DstAlpha, {0.75f, 0.75f, 0.75f, 0.75f}},
      {BlendFactor::OneMinusDstAlpha, {0.25f, 0.25f, 0.25f, 0.25f}},
      {BlendFactor::ConstantColor, {0.375f, 0.625f, 0.875f, 0.25f}},
      {BlendFactor::OneMinusConstantColor, {0.625f, 0.375f, 0.125f, 0.75f}},
  };
  for (const Row& r : rows) {
    EXPECT_EQ(blend(kSrc, kDst, state(BlendOp::Add, r.factor, BlendFactor::Zero)), kSrc * r.value)
        << "source factor " << int(r.factor);
    EXPECT_EQ(blend(kSrc, kDst, state(BlendOp::Add, BlendFactor::Zero, r.factor)), kDst * r.value)
        << "destination factor " << int(r.factor);
  }
}

TEST(Blend, ColourAndAlphaAreSeparate) {
  BlendState s = state(BlendOp::Add, BlendFactor::One, BlendFactor::One);
  s.alphaOp = BlendOp::Max;
  s.srcAlpha = BlendFactor::Zero;
  EXPECT_EQ(blend(kSrc, kDst, s), glm::vec4(0.75f, 0.75f, 0.875f, 0.75f));
  s.alphaOp = BlendOp::Add;
  s.dstAlpha = BlendFactor::OneMinusConstantColor;  // alpha takes 1 - constant.a = 0.75
  EXPECT_EQ(blend(kSrc, kDst, s).a, 0.5625f);
}

TEST(Blend, SourceAndConstantAreClampedAndDisabledPassesThrough) {
  const glm::vec4 wild(1.5f, -0.5f, std::numeric_limits<float>::quiet_NaN(), 2.0f);
  EXPECT_EQ(blend(wild, kDst, state(BlendOp::Add, BlendFactor::One, BlendFactor::Zero)),
            glm::vec4(1, 0, 0, 1));
  BlendState s = state(BlendOp::Add, BlendFactor::ConstantColor, BlendFactor::Zero);
  s.constant = glm::vec4(2.0f, -1.0f, 0.5f, 0.5f);
  EXPECT_EQ(blend(glm::vec4(0.5f), kDst, s), glm::vec4(0.5f, 0.0f, 0.25f, 0.25f));
  BlendState off = state(BlendOp::Subtract, BlendFactor::Zero, BlendFactor::One);
  off.enable = false;
  const glm::vec4 out = blend(glm::vec4(1.5f, -0.5f, 0.25f, 1.0f), kDst, off);
  EXPECT_EQ(out, glm::vec4(1.5f, -0.5f, 0.25f, 1.0f));
}

TEST(Blend, Rgba8PathAsTheMergeTakesIt) {
  // Keeping the destination (src factor zero, dst one) returns every stored byte unchanged.
  const BlendState keep = state(BlendOp::Add, BlendFactor::Zero, BlendFactor::One);
  for (uint32_t b = 0; b < 256; ++b) {
    const PackedColor stored = b | ((255 - b) << 8) | ((b ^ 0x5A) << 16) | (b << 24);
    ASSERT_EQ(blendAndPack(glm::vec4(0.3f), stored, keep), stored) << b;
  }
  // Red at half alpha over opaque blue: (0.5, 0, 0.5), alpha 0.5 + 1 * 0.5.
  const PackedColor blue = 0xFFFF0000u;
  EXPECT_EQ(blendAndPack(glm::vec4(1, 0, 0, 0.5f), blue, BlendState::alphaBlend()), 0xFF800080u);
  // Additive overflow and subtractive underflow clamp when packed.
  EXPECT_EQ(blendAndPack(glm::vec4(1.0f), 0xFFFFFFFFu, state(BlendOp::Add, BlendFactor::One, BlendFactor::One)),
            0xFFFFFFFFu);
  EXPECT_EQ(blendAndPack(glm::vec4(0.0f), 0xFFFFFFFFu,
                         state(BlendOp::Subtract, BlendFactor::One, BlendFactor::One)),
            0u);
}

TEST(Blend, WriteMaskKeepsUnmaskedChannels) {
  const PackedColor written = 0x44332211u, stored = 0xDDCCBBAAu;
  EXPECT_EQ(applyWriteMask(written, stored, kWriteAll), written);
  EXPECT_EQ(applyWriteMask(written, stored, kWriteNone), stored);
  EXPECT_EQ(applyWriteMask(written, stored, kWriteRed), 0xDDCCBB11u);
  EXPECT_EQ(applyWriteMask(written, stored, kWriteGreen | kWriteAlpha), 0x44CC22AAu);
  EXPECT_EQ(applyWriteMask(written, stored, kWriteBlue), 0xDD33BBAAu);
  // Masked blending: only alpha of the "over" result lands.
  EXPECT_EQ(blendAndPack(glm::vec4(1, 0, 0, 0.5f), 0x00FF0000u, BlendState::alphaBlend(), kWriteAlpha),
            0x80FF0000u);
}

}  // namespace
}  // namespace rast
