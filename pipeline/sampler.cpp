#include "pipeline/sampler.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace rast {
namespace {

// The coordinate reduced to one period of its addressing mode (see sampler.h).
float reduce(float u, AddressMode mode) {
  if (!std::isfinite(u)) return 0.0f;
  switch (mode) {
    case AddressMode::Repeat: return u - std::floor(u);
    case AddressMode::MirrorRepeat: return u - 2.0f * std::floor(0.5f * u);
    case AddressMode::ClampToEdge: return std::clamp(u, -1.0f, 2.0f);
  }
  return u;
}

// A texel index (within a few periods of [0, n)) mapped into [0, n).
int address(int i, int n, AddressMode mode) {
  switch (mode) {
    case AddressMode::Repeat: return ((i % n) + n) % n;
    case AddressMode::ClampToEdge: return std::clamp(i, 0, n - 1);
    case AddressMode::MirrorRepeat: {
      const int p = ((i % (2 * n)) + 2 * n) % (2 * n);
      return p < n ? p : 2 * n - 1 - p;
    }
  }
  return i;
}

}  // namespace

float lodFromGradients(glm::vec2 dUVdx, glm::vec2 dUVdy, int width, int height) {
  const glm::vec2 size{float(width), float(height)};
  const float rho = std::max(glm::length(dUVdx * size), glm::length(dUVdy * size));
  return std::log2(rho);  // -inf for a zero footprint: magnification, level 0
}

glm::vec4 TextureSampler::nearest(const TextureLevel& level, glm::vec2 uv) const {
  const float x = reduce(uv.x, state_.addressU) * float(level.width);
  const float y = reduce(uv.y, state_.addressV) * float(level.height);
  return level.at(address(int(std::floor(x)), level.width, state_.addressU),
                  address(int(std::floor(y)), level.height, state_.addressV));
}

glm::vec4 TextureSampler::bilinear(const TextureLevel& level, glm::vec2 uv) const {
  const float x = reduce(uv.x, state_.addressU) * float(level.width) - 0.5f;
  const float y = reduce(uv.y, state_.addressV) * float(level.height) - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const float fx = x - fx0, fy = y - fy0;
  const int ix = int(fx0), iy = int(fy0);
  const int x0 = address(ix, level.width, state_.addressU);
  const int x1 = address(ix + 1, level.width, state_.addressU);
  const int y0 = address(iy, level.height, state_.addressV);
  const int y1 = address(iy + 1, level.height, state_.addressV);
  const glm::vec4 top = level.at(x0, y0) * (1.0f - fx) + level.at(x1, y0) * fx;
  const glm::vec4 bottom = level.at(x0, y1) * (1.0f - fx) + level.at(x1, y1) * fx;
  return top * (1.0f - fy) + bottom * fy;
}

glm::vec4 TextureSampler::sample(glm::vec2 uv, float lod) const {
  const int last = texture_->levelCount() - 1;
  if (last < 0) return glm::vec4(0.0f);  // an empty Texture()
  lod = lod == lod ? std::clamp(lod, 0.0f, float(last)) : 0.0f;
  switch (state_.filter) {
    case TextureFilter::Nearest:
      return nearest(texture_->level(int(std::floor(lod + 0.5f))), uv);
    case TextureFilter::Bilinear:
      return bilinear(texture_->level(int(std::floor(lod + 0.5f))), uv);
    case TextureFilter::Trilinear: {
      const int l0 = int(std::floor(lod));
      const float f = lod - float(l0);
      const glm::vec4 a = bilinear(texture_->level(l0), uv);
      if (f == 0.0f) return a;
      return a * (1.0f - f) + bilinear(texture_->level(l0 + 1), uv) * f;
    }
  }
  return glm::vec4(0.0f);
}

}  // namespace rast
