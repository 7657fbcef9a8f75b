#include "debug/rgb_image.h"

#include <algorithm>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

namespace rast {
namespace {

Status write(const RgbImage& image, const std::string& path, OIIO::Filesystem::IOProxy* proxy) {
  auto out = OIIO::ImageOutput::create("image.png", proxy);
  if (!out) return Status::error(path + ": cannot create a PNG writer");
  const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) ||
      !out->close())
    return Status::error(path + ": cannot write image: " + out->geterror());
  return Status::ok();
}

}  // namespace

void RgbImage::fillRect(int x0, int y0, int x1, int y1, Rgb c) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width);
  y1 = std::min(y1, height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) at(x, y) = c;
}

Status writePng(const RgbImage& image, const std::string& path) {
  return write(image, path, nullptr);
}

Status encodePng(const RgbImage& image, std::vector<unsigned char>& out) {
  out.clear();
  OIIO::Filesystem::IOVecOutput proxy(out);
  return write(image, "image.png", &proxy);
}

std::string pngDataUri(const std::vector<unsigned char>& png) {
  return "data:image/png;base64," +
         OIIO::Strutil::base64_encode(OIIO::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace rast
