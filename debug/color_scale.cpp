#include "debug/color_scale.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rast {
namespace {

// Anchor colours of the viridis scale at t = 0, 1/8, ..., 1, interpolated linearly.
constexpr std::array<std::array<double, 3>, 9> kViridis = {{
    {68, 1, 84}, {71, 44, 122}, {59, 81, 139}, {44, 113, 142}, {33, 144, 141},
    {39, 173, 129}, {92, 200, 99}, {170, 220, 50}, {253, 231, 37}}};

// 3x5 glyphs, one row per entry, bit 2 the left column.
struct Glyph {
  char c;
  std::array<uint8_t, 5> rows;
};
constexpr std::array<Glyph, 15> kGlyphs = {{
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}},
    {'3', {7, 1, 7, 1, 7}}, {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}},
    {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}}, {'8', {7, 5, 7, 5, 7}},
    {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
    {'+', {0, 2, 7, 2, 0}}, {'e', {0, 7, 7, 4, 7}}, {' ', {0, 0, 0, 0, 0}}}};

const Glyph* glyph(char c) {
  for (const Glyph& g : kGlyphs)
    if (g.c == c) return &g;
  return nullptr;
}

constexpr Rgb kLegendBackground{24, 24, 24};
constexpr Rgb kLegendText{235, 235, 235};

}  // namespace

Rgb viridis(double t) {
  t = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * (kViridis.size() - 1);
  const size_t i = std::min(size_t(t), kViridis.size() - 2);
  const double f = t - double(i);
  auto channel = [&](int k) {
    return uint8_t(std::lround(kViridis[i][k] + (kViridis[i + 1][k] - kViridis[i][k]) * f));
  };
  return {channel(0), channel(1), channel(2)};
}

Rgb idColor(uint64_t id) {
  // Golden-ratio steps around the hue circle, alternating lightness, so neighbours differ.
  const double hue = std::fmod(double(id) * 0.6180339887498949, 1.0) * 6.0;
  const double light = (id % 2) ? 0.95 : 0.7;
  const int sector = int(hue);
  const double f = hue - sector;
  double r = 0, g = 0, b = 0;
  switch (sector % 6) {
    case 0: r = 1, g = f, b = 0; break;
    case 1: r = 1 - f, g = 1, b = 0; break;
    case 2: r = 0, g = 1, b = f; break;
    case 3: r = 0, g = 1 - f, b = 1; break;
    case 4: r = f, g = 0, b = 1; break;
    default: r = 1, g = 0, b = 1 - f; break;
  }
  auto channel = [&](double v) { return uint8_t(std::lround((0.25 + 0.75 * v) * light * 255.0)); };
  return {channel(r), channel(g), channel(b)};
}

int textWidth(const std::string& text, int scale) { return int(text.size()) * 4 * scale; }

int drawText(RgbImage& image, int x, int y, const std::string& text, Rgb color, int scale) {
  int cx = x;
  for (char c : text) {
    if (const Glyph* g = glyph(c))
      for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 3; ++col)
          if (g->rows[size_t(row)] & (4 >> col))
            image.fillRect(cx + col * scale, y + row * scale, cx + (col + 1) * scale,
                           y + (row + 1) * scale, color);
    cx += 4 * scale;
  }
  return cx - x;
}

RgbImage withLegend(const RgbImage& image, const Legend& legend) {
  constexpr int kScale = 2, kBarHeight = 12, kPad = 6;
  const int textHeight = 5 * kScale;
  RgbImage out(image.width, image.height + kPad + kBarHeight + kPad + textHeight + kPad,
               kLegendBackground);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) out.at(x, y) = image.at(x, y);
  const int barTop = image.height + kPad, textTop = barTop + kBarHeight + kPad;
  int barLeft = kPad;
  if (legend.hasSpecial) {
    const int w = std::max(kBarHeight, textWidth(legend.specialLabel, kScale));
    out.fillRect(barLeft, barTop, barLeft + w, barTop + kBarHeight, legend.special);
    drawText(out, barLeft, textTop, legend.specialLabel, kLegendText, kScale);
    barLeft += w + kPad;
  }
  const int barRight = std::max(barLeft + 1, out.width - kPad);
  for (int x = barLeft; x < barRight; ++x)
    out.fillRect(x, barTop, x + 1, barTop + kBarHeight,
                 viridis(barRight - barLeft > 1 ? double(x - barLeft) / (barRight - barLeft - 1) : 1.0));
  drawText(out, barLeft, textTop, legend.low, kLegendText, kScale);
  drawText(out, std::max(barLeft, barRight - textWidth(legend.high, kScale)), textTop, legend.high,
           kLegendText, kScale);
  return out;
}

RgbImage enlarge(const RgbImage& image, int factor) {
  if (factor <= 1) return image;
  RgbImage out(image.width * factor, image.height * factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) out.at(x, y) = image.at(x / factor, y / factor);
  return out;
}

int enlargementFor(int width, int height, int minSide) {
  const int longer = std::max(width, height);
  return std::max(1, (minSide + longer - 1) / longer);
}

}  // namespace rast
