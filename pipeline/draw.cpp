#include "pipeline/draw.h"

#include <string>

namespace rast {

PixelRect drawableRect(const Framebuffer& fb, const PipelineState& state) {
  const Viewport& vp = state.viewport;
  PixelRect rect = PixelRect{vp.x, vp.y, vp.x + vp.width, vp.y + vp.height}.intersect(
      PixelRect{0, 0, fb.width(), fb.height()});
  if (state.scissor) rect = rect.intersect(*state.scissor);
  return rect;
}

Status validateDrawState(const Framebuffer& fb, const PipelineState& state, size_t indexCount) {
  const FixedPointFormat f = state.format;
  if (!f.valid())
    return Status::error("fixed-point format " + f.name() +
                         " is not supported: fraction bits must be 1..8 and integer + fraction "
                         "bits at most 28");
  const Viewport& vp = state.viewport;
  if (vp.width <= 0 || vp.height <= 0)
    return Status::error("viewport size " + std::to_string(vp.width) + "x" +
                         std::to_string(vp.height) + " must be positive");
  const double guard = f.guardBandPixels();
  if (vp.x < -guard || vp.y < -guard || double(vp.x) + vp.width > guard ||
      double(vp.y) + vp.height > guard)
    return Status::error("viewport (" + std::to_string(vp.x) + ", " + std::to_string(vp.y) +
                         ") " + std::to_string(vp.width) + "x" + std::to_string(vp.height) +
                         " exceeds the " + f.name() + " fixed-point range of +-" +
                         std::to_string(int64_t(guard)) + " pixels");
  if (fb.width() > kMaxFramebufferSide || fb.height() > kMaxFramebufferSide)
    return Status::error("framebuffer " + std::to_string(fb.width()) + "x" +
                         std::to_string(fb.height()) + " exceeds " +
                         std::to_string(kMaxFramebufferSide) + " pixels a side");
  if (double(fb.width()) > guard || double(fb.height()) > guard)
    return Status::error("framebuffer exceeds the " + f.name() + " fixed-point range");
  if (fb.samples() > 1 && f.fractionBits < 4)
    return Status::error("MSAA sample positions lie on a 1/16-pixel grid: " +
                         std::to_string(fb.samples()) + " samples need at least 4 subpixel "
                         "bits, the format is " + f.name());
  if (fb.samples() > 1 && state.rasterMode == RasterMode::Float)
    return Status::error("the float raster mode covers pixel centres only: it has no MSAA");
  if (indexCount % 3 != 0)
    return Status::error("index count " + std::to_string(indexCount) +
                         " is not a multiple of 3");
  // Set-up triangles are named by 16 bits of chunk and 15 of place (front_end.h); a bin entry's
  // 32nd bit is a flag (bin.h).
  if (indexCount / 3 > (size_t{1} << 28))
    return Status::error("a draw holds at most 2^28 triangles; split the " +
                         std::to_string(indexCount / 3) + "-triangle draw");
  return Status::ok();
}

Status validateIndices(size_t vertexCount, std::span<const uint32_t> indices) {
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= vertexCount)
      return Status::error("index " + std::to_string(i) + " has value " +
                           std::to_string(indices[i]) + ", out of range for " +
                           std::to_string(vertexCount) + " vertices");
  return Status::ok();
}

Status validateDraw(const Framebuffer& fb, const PipelineState& state, size_t vertexCount,
                    std::span<const uint32_t> indices) {
  if (Status s = validateDrawState(fb, state, indices.size()); !s) return s;
  return validateIndices(vertexCount, indices);
}

}  // namespace rast
