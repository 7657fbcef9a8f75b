// Texture mapping: a vertex with texture coordinates, a shader that samples with the footprint
// of the pixel (sampleGrad from the screen-space derivatives the pipeline supplies, which
// selects the mip level and so filters perspective minification), and a procedural checkerboard.
#pragma once

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "pipeline/sampler.h"
#include "pipeline/shader.h"

namespace rast {

struct TexturedVertex {
  glm::vec3 position{0.0f};
  glm::vec2 uv{0.0f};
};

// Passes the texture coordinates on as varyings 0..1.
struct TexturedVertexShader {
  using Vertex = TexturedVertex;
  static constexpr int kVaryings = 2;
  glm::mat4 modelViewProjection{1.0f};

  ShadedVertex<2> operator()(const Vertex& v) const {
    return {modelViewProjection * glm::vec4(v.position, 1.0f), {v.uv.x, v.uv.y}};
  }
};

struct TexturedShader {
  static constexpr int kVaryings = 2;
  static constexpr bool kMayDiscard = false;
  static constexpr bool kDerivatives = true;
  TextureSampler sampler;

  PixelResult operator()(const Fragment<2>& f) const {
    const glm::vec4 c = sampler.sampleGrad({f.varyings[0], f.varyings[1]}, {f.ddx[0], f.ddx[1]},
                                           {f.ddy[0], f.ddy[1]});
    return {glm::vec4(c.r, c.g, c.b, 1.0f)};
  }
};

// A size x size checkerboard of squares x squares cells, `a` in the top-left cell, mipmapped.
// size must be a multiple of squares (so every cell has the same texels).
inline Status checkerboardTexture(int size, int squares, glm::vec4 a, glm::vec4 b, Texture& out) {
  if (squares < 1 || size < squares || size % squares != 0)
    return Status::error("checkerboard: size " + std::to_string(size) +
                         " is not a positive multiple of " + std::to_string(squares) + " squares");
  const int cell = size / squares;
  std::vector<glm::vec4> texels(size_t(size) * size_t(size));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      texels[size_t(y) * size + x] = ((x / cell + y / cell) % 2 == 0) ? a : b;
  return Texture::fromPixels(size, size, texels, out);
}

}  // namespace rast
