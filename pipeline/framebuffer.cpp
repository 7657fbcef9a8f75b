#include "pipeline/framebuffer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <OpenImageIO/imageio.h>

namespace rast {
namespace {

Status writeImage(const std::string& path, int width, int height, int channels,
                  OIIO::TypeDesc type, const void* pixels) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return Status::error("cannot write '" + path + "': " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, type);
  if (!out->open(path, spec) || !out->write_image(type, pixels) || !out->close())
    return Status::error("cannot write '" + path + "': " + out->geterror());
  return Status::ok();
}

// Binary PGM with 16-bit samples, most significant byte first (the format's rule). Written here
// because OpenImageIO 2.4's PNM writer stores 16-bit data as 8-bit or bit-packed samples.
Status writePgm16(const std::string& path, int width, int height, const std::vector<uint16_t>& v) {
  std::ofstream out(path, std::ios::binary);
  out << "P5\n" << width << " " << height << "\n65535\n";
  for (uint16_t s : v) out.put(char(s >> 8)).put(char(s & 255));
  if (!out.flush()) return Status::error("cannot write '" + path + "'");
  return Status::ok();
}

bool hasExtension(const std::string& path, const char* ext) {
  const size_t n = std::strlen(ext);
  if (path.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(path[path.size() - n + i])) != ext[i]) return false;
  return true;
}

}  // namespace

glm::vec4 unpackColor(PackedColor c) {
  return glm::vec4(float(c & 255), float((c >> 8) & 255), float((c >> 16) & 255),
                   float(c >> 24)) / 255.0f;
}

Framebuffer::Framebuffer(int width, int height, bool withCounts, int samples)
    : width_(width), height_(height), samples_(samples) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("framebuffer size must be positive");
  if (!SamplePattern::supported(samples))
    throw std::invalid_argument("framebuffer samples must be 1, 4 or 8");
  const size_t n = size_t(width) * size_t(height);
  color_.assign(n * size_t(samples), 0);
  depth_.assign(n * size_t(samples), 1.0f);
  if (withCounts) counts_.assign(n, 0);
}

PackedColor Framebuffer::color(int x, int y) const {
  if (samples_ == 1) return color_[index(x, y)];
  uint32_t sum[4] = {0, 0, 0, 0};
  for (int s = 0; s < samples_; ++s) {
    const PackedColor c = sampleColor(x, y, s);
    for (int k = 0; k < 4; ++k) sum[k] += (c >> (8 * k)) & 255;
  }
  PackedColor out = 0;
  for (int k = 0; k < 4; ++k) out |= ((sum[k] + uint32_t(samples_) / 2) / uint32_t(samples_)) << (8 * k);
  return out;
}

std::vector<PackedColor> Framebuffer::resolvedColor() const {
  if (samples_ == 1) return color_;
  std::vector<PackedColor> out(pixelCount());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) out[index(x, y)] = color(x, y);
  return out;
}

void Framebuffer::clear(glm::vec4 color, float depth) {
  std::fill(color_.begin(), color_.end(), packColor(color));
  std::fill(depth_.begin(), depth_.end(), depth);
}

void Framebuffer::clearCounts() { std::fill(counts_.begin(), counts_.end(), 0u); }

Status writeColorImage(const Framebuffer& fb, const std::string& path) {
  const std::vector<PackedColor> resolved = fb.resolvedColor();
  return writeImage(path, fb.width(), fb.height(), 4, OIIO::TypeDesc::UINT8, resolved.data());
}

Status writeDepthImage(const Framebuffer& fb, const std::string& path) {
  return writeImage(path, fb.width(), fb.height(), 1, OIIO::TypeDesc::FLOAT,
                    fb.depthPlane().data());  // sample 0: the first plane
}

Status writeCountImage(const Framebuffer& fb, const std::string& path) {
  if (!fb.hasCounts()) return Status::error("the framebuffer keeps no counts");
  std::vector<uint16_t> grey(fb.countPlane().size());
  bool saturated = false;
  std::transform(fb.countPlane().begin(), fb.countPlane().end(), grey.begin(), [&](uint32_t c) {
    saturated |= c > 65535;
    return uint16_t(std::min<uint32_t>(c, 65535));
  });
  Status s = hasExtension(path, ".pgm")
                 ? writePgm16(path, fb.width(), fb.height(), grey)
                 : writeImage(path, fb.width(), fb.height(), 1, OIIO::TypeDesc::UINT16, grey.data());
  if (s && saturated) return Status::error("count image '" + path + "' saturated at 65535");
  return s;
}

}  // namespace rast
