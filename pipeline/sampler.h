// Texture sampling: nearest, bilinear and trilinear filters; repeat, clamp-to-edge and mirrored
// repeat addressing; level of detail given, or from screen-space derivatives of the coordinates.
//
// Conventions (OpenGL's and Direct3D's): u runs right and v down over level 0's rows, texel (i, j)
// of a w x h level covers [i/w, (i+1)/w] x [j/h, (j+1)/h] with its centre at ((i + 0.5)/w, ...).
// Bilinear filtering weighs the four texels around u*w - 0.5, v*h - 0.5, so a sample at a texel
// centre returns that texel exactly (the other weights are exactly 0).
//
// Mip levels: Nearest and Bilinear use the nearest level, round(lod) with halves up (OpenGL's
// *_MIPMAP_NEAREST); Trilinear blends the bilinear samples of floor(lod) and floor(lod) + 1 by
// the fraction (LINEAR_MIPMAP_LINEAR). lod is clamped to [0, levelCount - 1]; a NaN lod is 0.
//
// Level of detail from derivatives (the formula of the OpenGL and Vulkan specifications,
// isotropic): with dUVdx, dUVdy the screen-space derivatives of (u, v) and (w, h) level 0's size,
//   lod = log2(max(|dUVdx * (w, h)|, |dUVdy * (w, h)|))
// i.e. log2 of the longer side of the pixel's footprint in level-0 texels.
//
// Addressing, on integer texel indices of the level: Repeat wraps (i mod n); ClampToEdge clamps
// to [0, n - 1]; MirrorRepeat reflects with period 2n (0 1 .. n-1 n-1 .. 1 0 0 1 ..). A
// non-finite coordinate reads as 0; coordinates are reduced to one period (Repeat: u - floor(u),
// exact in float; Mirror: u - 2 floor(u/2); Clamp: clamped to [-1, 2]) before scaling, so no
// coordinate can overflow an index.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "pipeline/texture.h"

namespace rast {

enum class TextureFilter { Nearest, Bilinear, Trilinear };
enum class AddressMode { Repeat, ClampToEdge, MirrorRepeat };

struct SamplerState {
  TextureFilter filter = TextureFilter::Trilinear;
  AddressMode addressU = AddressMode::Repeat;
  AddressMode addressV = AddressMode::Repeat;
};

// The level of detail of a footprint (formula above).
float lodFromGradients(glm::vec2 dUVdx, glm::vec2 dUVdy, int width, int height);

// A texture with a sampler state, as a shader holds it. The texture must outlive it.
class TextureSampler {
 public:
  TextureSampler(const Texture& texture, SamplerState state) : texture_(&texture), state_(state) {}

  const Texture& texture() const { return *texture_; }
  const SamplerState& state() const { return state_; }

  glm::vec4 sample(glm::vec2 uv, float lod) const;
  glm::vec4 sampleGrad(glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy) const {
    return sample(uv, lodFromGradients(dUVdx, dUVdy, texture_->width(), texture_->height()));
  }

 private:
  glm::vec4 nearest(const TextureLevel& level, glm::vec2 uv) const;
  glm::vec4 bilinear(const TextureLevel& level, glm::vec2 uv) const;

  const Texture* texture_;
  SamplerState state_;
};

}  // namespace rast
