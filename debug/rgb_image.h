// An 8-bit RGB image for debugging pictures, and its PNG encoding (OpenImageIO).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/status.h"

namespace rast {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(Rgb, Rgb) = default;
};

struct RgbImage {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;  // row-major, row 0 at the top

  RgbImage() = default;
  RgbImage(int w, int h, Rgb fill = {}) : width(w), height(h), pixels(size_t(w) * size_t(h), fill) {}
  Rgb& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  Rgb at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  void fillRect(int x0, int y0, int x1, int y1, Rgb c);  // [x0, x1) x [y0, y1), clipped
};

Status writePng(const RgbImage& image, const std::string& path);
// The PNG file's bytes, for embedding.
Status encodePng(const RgbImage& image, std::vector<unsigned char>& out);
std::string pngDataUri(const std::vector<unsigned char>& png);

}  // namespace rast
