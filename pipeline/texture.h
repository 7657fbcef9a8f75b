// Textures: a mip chain of linear float RGBA images, loaded through OpenImageIO or built from
// pixels in memory. Sampling (filters, addressing, level of detail) is in pipeline/sampler.h.
//
// Mip chain: level k is max(1, floor(w / 2^k)) x max(1, floor(h / 2^k)) (OpenGL's and Direct3D's
// rule, so non-power-of-two sizes work), down to 1x1. Each level is resized from the one above
// by OpenImageIO's ImageBufAlgo::resize with a Blackman-Harris filter (width 3 destination
// texels, scaled to the actual ratio): unlike a 2x2 box it maps the source onto the destination
// at the true ratio (5 -> 2 texels is a factor 2.5, not 2), and unlike Lanczos it has no negative
// lobes, so a checkerboard gets no ringing or values outside the source range.
//
// Colour: texels are linear. 8- and 16-bit files whose colour space OpenImageIO reports as sRGB
// (PNG and JPEG by default) are converted from sRGB to linear on load (the RGB channels, not
// alpha, by OpenImageIO's colorconvert); float files (EXR) are taken as linear. Alpha is filtered
// as stored (not premultiplied).
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "pipeline/status.h"

namespace rast {

struct TextureLevel {
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;  // row-major, row 0 at the top (v = 0)

  const glm::vec4& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
};

// The size of mip level `level` of a width x height texture, and the number of levels.
int mipLevelExtent(int extent, int level);
int mipLevelCount(int width, int height);

// Largest accepted texture side; beyond it an image is an error, not an allocation failure.
inline constexpr int kMaxTextureSize = 16384;

class Texture {
 public:
  Texture() = default;

  int width() const { return levels_.empty() ? 0 : levels_[0].width; }
  int height() const { return levels_.empty() ? 0 : levels_[0].height; }
  int levelCount() const { return int(levels_.size()); }
  const TextureLevel& level(int k) const { return levels_[size_t(k)]; }

  // Level 0 from row-major texels, the rest built by filtering (see above); `mipmaps` false keeps
  // level 0 alone. Errors: a size outside 1..kMaxTextureSize, a texel count that does not match,
  // a non-finite texel.
  static Status fromPixels(int width, int height, std::span<const glm::vec4> texels, Texture& out,
                           bool mipmaps = true);
  // Every level given explicitly (tests: a chain of distinct constant colours). The sizes must be
  // the chain's: mipLevelExtent of level 0's for each level, any count from 1 to the full chain.
  static Status fromLevels(std::vector<TextureLevel> levels, Texture& out);

 private:
  std::vector<TextureLevel> levels_;
};

enum class ColorEncoding {
  FromFile,  // sRGB where the file says so (see above), else linear
  Srgb,      // decode RGB from sRGB whatever the file says
  Linear,    // take the values as they are
};

// Loads an image (PNG, EXR, or any format OpenImageIO reads) as a mipmapped texture. One to four
// channels: grey (replicated to RGB), grey + alpha, RGB, RGBA; missing alpha is 1. Errors name
// the file: missing, not a readable image format, unreadable, a channel count or size out of
// range, non-finite texels.
Status loadTexture(const std::string& path, Texture& out,
                   ColorEncoding encoding = ColorEncoding::FromFile);

}  // namespace rast
