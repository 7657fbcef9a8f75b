#include "pipeline/texture.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

namespace rast {
namespace {

// OpenImageIO's messages can span lines; a Status message is one line.
std::string oneLine(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

bool allFinite(std::span<const glm::vec4> texels, size_t& bad) {
  for (size_t i = 0; i < texels.size(); ++i) {
    const glm::vec4& t = texels[i];
    if (!std::isfinite(t.r) || !std::isfinite(t.g) || !std::isfinite(t.b) || !std::isfinite(t.a)) {
      bad = i;
      return false;
    }
  }
  return true;
}

OIIO::ImageSpec rgbaSpec(int width, int height) {
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
  spec.alpha_channel = 3;
  return spec;
}

TextureLevel downsample(const TextureLevel& src, int width, int height) {
  // resize reads the source only; ImageBuf's wrapping constructor takes a non-const pointer.
  const OIIO::ImageBuf in(rgbaSpec(src.width, src.height),
                          const_cast<glm::vec4*>(src.texels.data()));
  OIIO::ImageBuf out(rgbaSpec(width, height));
  // One thread: the caller decides about parallelism, and the result is the same either way.
  OIIO::ImageBufAlgo::resize(out, in, "blackman-harris", 3.0f, OIIO::ROI::All(), 1);
  TextureLevel level{width, height, std::vector<glm::vec4>(size_t(width) * size_t(height))};
  out.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, level.texels.data());
  return level;
}

Status checkSize(int width, int height, const std::string& what) {
  if (width < 1 || height < 1 || width > kMaxTextureSize || height > kMaxTextureSize)
    return Status::error(what + ": size " + std::to_string(width) + "x" + std::to_string(height) +
                         " is outside 1.." + std::to_string(kMaxTextureSize));
  return Status::ok();
}

}  // namespace

int mipLevelExtent(int extent, int level) { return std::max(1, extent >> level); }

int mipLevelCount(int width, int height) {
  return std::bit_width(unsigned(std::max(width, height)));  // floor(log2(max)) + 1
}

Status Texture::fromPixels(int width, int height, std::span<const glm::vec4> texels, Texture& out,
                           bool mipmaps) {
  if (Status s = checkSize(width, height, "texture"); !s) return s;
  if (texels.size() != size_t(width) * size_t(height))
    return Status::error("texture: " + std::to_string(texels.size()) + " texels for a " +
                         std::to_string(width) + "x" + std::to_string(height) + " image");
  if (size_t bad; !allFinite(texels, bad))
    return Status::error("texture: texel (" + std::to_string(bad % size_t(width)) + ", " +
                         std::to_string(bad / size_t(width)) + ") is not finite");
  Texture t;
  t.levels_.push_back({width, height, std::vector<glm::vec4>(texels.begin(), texels.end())});
  const int count = mipmaps ? mipLevelCount(width, height) : 1;
  for (int k = 1; k < count; ++k)
    t.levels_.push_back(
        downsample(t.levels_.back(), mipLevelExtent(width, k), mipLevelExtent(height, k)));
  out = std::move(t);
  return Status::ok();
}

Status Texture::fromLevels(std::vector<TextureLevel> levels, Texture& out) {
  if (levels.empty()) return Status::error("texture: no levels");
  const int width = levels[0].width, height = levels[0].height;
  if (Status s = checkSize(width, height, "texture"); !s) return s;
  if (levels.size() > size_t(mipLevelCount(width, height)))
    return Status::error("texture: " + std::to_string(levels.size()) + " levels, a " +
                         std::to_string(width) + "x" + std::to_string(height) + " chain has " +
                         std::to_string(mipLevelCount(width, height)));
  for (size_t k = 0; k < levels.size(); ++k) {
    const TextureLevel& l = levels[k];
    const int w = mipLevelExtent(width, int(k)), h = mipLevelExtent(height, int(k));
    const std::string name = "texture level " + std::to_string(k);
    if (l.width != w || l.height != h)
      return Status::error(name + ": size " + std::to_string(l.width) + "x" +
                           std::to_string(l.height) + ", expected " + std::to_string(w) + "x" +
                           std::to_string(h));
    if (l.texels.size() != size_t(w) * size_t(h))
      return Status::error(name + ": " + std::to_string(l.texels.size()) + " texels, expected " +
                           std::to_string(size_t(w) * size_t(h)));
    if (size_t bad; !allFinite(l.texels, bad))
      return Status::error(name + ": a texel is not finite");
  }
  out.levels_ = std::move(levels);
  return Status::ok();
}

Status loadTexture(const std::string& path, Texture& out, ColorEncoding encoding) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return Status::error(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) return Status::error(path + ": is a directory");
  // Alpha as stored: OpenImageIO would otherwise premultiply the colour of PNGs by it.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in)
    return Status::error(path + ": not an image format OpenImageIO can read (" +
                         oneLine(OIIO::geterror()) + ")");
  const OIIO::ImageSpec& spec = in->spec();
  const int channels = spec.nchannels;
  if (channels < 1 || channels > 4)
    return Status::error(path + ": " + std::to_string(channels) +
                         " channels; textures take 1 to 4 (grey, grey+alpha, RGB, RGBA)");
  if (Status s = checkSize(spec.width, spec.height, path); !s) return s;
  const size_t count = size_t(spec.width) * size_t(spec.height);
  std::vector<float> raw(count * size_t(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data()))
    return Status::error(path + ": cannot read pixels (" + oneLine(in->geterror()) + ")");

  std::vector<glm::vec4> texels(count);
  for (size_t i = 0; i < count; ++i) {
    const float* p = &raw[i * size_t(channels)];
    switch (channels) {
      case 1: texels[i] = glm::vec4(p[0], p[0], p[0], 1.0f); break;
      case 2: texels[i] = glm::vec4(p[0], p[0], p[0], p[1]); break;
      case 3: texels[i] = glm::vec4(p[0], p[1], p[2], 1.0f); break;
      default: texels[i] = glm::vec4(p[0], p[1], p[2], p[3]); break;
    }
  }
  const bool srgb =
      encoding == ColorEncoding::Srgb ||
      (encoding == ColorEncoding::FromFile &&
       OIIO::Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "sRGB"));
  if (srgb) {
    OIIO::ImageBuf buf(rgbaSpec(spec.width, spec.height), texels.data());
    if (!OIIO::ImageBufAlgo::colorconvert(buf, buf, "sRGB", "linear", false, "", "", nullptr,
                                          OIIO::ROI::All(), 1))
      return Status::error(path + ": cannot convert from sRGB (" + oneLine(buf.geterror()) + ")");
  }
  if (size_t bad; !allFinite(texels, bad))
    return Status::error(path + ": pixel (" + std::to_string(bad % size_t(spec.width)) + ", " +
                         std::to_string(bad / size_t(spec.width)) + ") is not finite");
  return Texture::fromPixels(spec.width, spec.height, texels, out);
}

}  // namespace rast
