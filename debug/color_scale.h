// Readable colour scales for debugging images: a perceptually ordered map (viridis-like) and a
// legend bar with its end values, written in a small built-in pixel font (no font files needed).
#pragma once

#include <string>

#include "debug/rgb_image.h"

namespace rast {

// t in [0, 1] (clamped) from dark blue-purple through teal and green to yellow.
Rgb viridis(double t);

// A distinct, stable colour for an integer id (ids next to each other differ clearly).
Rgb idColor(uint64_t id);

// Text in a 3x5 pixel font scaled by `scale`: digits, '.', '-', '+', 'e' and space. Returns the
// width drawn.
int drawText(RgbImage& image, int x, int y, const std::string& text, Rgb color, int scale = 2);
int textWidth(const std::string& text, int scale = 2);

// `image` with a legend below it: an optional swatch for a special value (e.g. "0" or "none"),
// then the colour bar from `low` to `high` labelled at both ends.
struct Legend {
  std::string low, high;
  bool hasSpecial = false;
  Rgb special;
  std::string specialLabel;
};
RgbImage withLegend(const RgbImage& image, const Legend& legend);

// Nearest-neighbour enlargement by an integer factor.
RgbImage enlarge(const RgbImage& image, int factor);
// The factor that makes the longer side at least `minSide` pixels.
int enlargementFor(int width, int height, int minSide = 256);

}  // namespace rast
