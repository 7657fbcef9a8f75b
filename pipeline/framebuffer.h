// The framebuffer: RGBA8 colour, 32-bit float depth and an optional per-pixel count of written
// fragments, each row-major with row 0 at the top. With MSAA (4 or 8 samples) colour and depth
// are kept per sample, one plane per sample index (plane s starts at s * width * height), and
// the colour image is their resolve.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>
#include <xmmintrin.h>

#include "pipeline/status.h"
#include "rasterizer/sample_pattern.h"

namespace rast {

// RGBA8 packed with red in the low byte (the byte order of an RGBA image in memory).
using PackedColor = uint32_t;

// Clamps each channel to [0, 1], NaN to 0 (a NaN never reaches the integer conversion), and rounds
// to the nearest of 0..255: v > 0 ? (v < 1 ? v : 1) : 0, as maxss(v, 0) = (v > 0 ? v : 0) then
// minss(that, 1), the same value for every v in two instructions whatever the compiler's float
// options (packRowColors in pipeline/tile_loop.h does the same four lanes at a time).
[[gnu::always_inline]] inline uint32_t colorByte(float v) {
  const float clamped =
      _mm_cvtss_f32(_mm_min_ss(_mm_max_ss(_mm_set_ss(v), _mm_setzero_ps()), _mm_set_ss(1.0f)));
  return uint32_t(clamped * 255.0f + 0.5f);
}
// Forced inline: the tile loop packs once per shaded lane (W1) or once per (triangle, tile) for a
// per-triangle shader (W2), and GCC had left it a call there (2 % of a W2 tiny-1 frame).
[[gnu::always_inline]] inline PackedColor packColor(glm::vec4 c) {
  return colorByte(c.r) | (colorByte(c.g) << 8) | (colorByte(c.b) << 16) | (colorByte(c.a) << 24);
}
glm::vec4 unpackColor(PackedColor c);

class Framebuffer {
 public:
  // `samples`: 1, 4 or 8 (SamplePattern::supported); anything else throws.
  Framebuffer(int width, int height, bool withCounts = false, int samples = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  size_t pixelCount() const { return size_t(width_) * size_t(height_); }
  bool hasCounts() const { return !counts_.empty(); }

  void clear(glm::vec4 color, float depth);
  void clearCounts();

  // The pixel's colour: with MSAA, the resolve of its samples.
  PackedColor color(int x, int y) const;
  float depth(int x, int y) const { return depth_[index(x, y)]; }  // sample 0
  uint32_t count(int x, int y) const { return counts_[index(x, y)]; }
  PackedColor sampleColor(int x, int y, int s) const { return color_[s * pixelCount() + index(x, y)]; }
  float sampleDepth(int x, int y, int s) const { return depth_[s * pixelCount() + index(x, y)]; }
  // One colour per pixel: the box-filter resolve of the samples (each channel's mean, rounded to
  // nearest, half up, in integers), or the colour plane itself without MSAA.
  std::vector<PackedColor> resolvedColor() const;

  std::vector<PackedColor>& colorPlane() { return color_; }
  std::vector<float>& depthPlane() { return depth_; }
  std::vector<uint32_t>& countPlane() { return counts_; }
  const std::vector<PackedColor>& colorPlane() const { return color_; }
  const std::vector<float>& depthPlane() const { return depth_; }
  const std::vector<uint32_t>& countPlane() const { return counts_; }

  size_t index(int x, int y) const { return size_t(y) * size_t(width_) + size_t(x); }

 private:
  int width_, height_, samples_;
  std::vector<PackedColor> color_;
  std::vector<float> depth_;
  std::vector<uint32_t> counts_;
};

// Image output through OpenImageIO; the format follows the file extension.
Status writeColorImage(const Framebuffer& fb, const std::string& path);  // .png, .exr, .tif ...
Status writeDepthImage(const Framebuffer& fb, const std::string& path);  // .exr (32-bit float)
// 16-bit grey (.png, .pgm): counts above 65535 saturate, and the call says so in its message.
Status writeCountImage(const Framebuffer& fb, const std::string& path);

}  // namespace rast
