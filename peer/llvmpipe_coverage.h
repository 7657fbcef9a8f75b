// Coverage through llvmpipe: window-space triangles drawn with additive blending into a 32-bit
// float count image, read back per pixel. The conformance test compares it with our pipeline's
// count image (tests/llvmpipe_conformance_test.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "peer/llvmpipe_context.h"

namespace rast::peer {

class LlvmpipeCoverage {
 public:
  // A width x height count image; both must be powers of two (see countCoverage). Null with
  // `error` set if llvmpipe is unavailable (LlvmpipeContext::create) or the image cannot be made.
  static std::unique_ptr<LlvmpipeCoverage> create(int width, int height, int threads,
                                                  std::string& error);
  ~LlvmpipeCoverage();
  LlvmpipeCoverage(const LlvmpipeCoverage&) = delete;
  LlvmpipeCoverage& operator=(const LlvmpipeCoverage&) = delete;

  const LlvmpipeContext& context() const { return *gl_; }

  // Whether (x, y), in our window coordinates, reaches llvmpipe's rasterizer unchanged: its NDC
  // value is a float from which llvmpipe's float viewport transform gives back exactly x and
  // height - y. True for every float on a grid of 2^-12 pixels inside the image, for instance.
  bool representable(glm::vec2 window) const;

  // Clears the count image, draws the triangles (three vertices each, our window coordinates:
  // origin top-left, y down) with GL_ONE, GL_ONE blending and no culling, depth or scissor, and
  // returns the number of triangles that covered each pixel, row 0 at the top. Every vertex
  // must be representable(); `error` is set otherwise, or on a GL error.
  std::vector<uint32_t> countCoverage(std::span<const glm::vec2> vertices, std::string& error);

 private:
  LlvmpipeCoverage() = default;
  glm::vec2 toNdc(glm::vec2 window) const;

  std::unique_ptr<LlvmpipeContext> gl_;
  int width_ = 0, height_ = 0;
  GLuint framebuffer_ = 0, countBuffer_ = 0, program_ = 0, vertexArray_ = 0, vertexBuffer_ = 0;
};

}  // namespace rast::peer
