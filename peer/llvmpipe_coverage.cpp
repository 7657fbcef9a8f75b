#include "peer/llvmpipe_coverage.h"

#include <cmath>

namespace rast::peer {
namespace {

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec2 position;
void main() { gl_Position = vec4(position, 0.0, 1.0); }
)";

constexpr const char* kFragmentShader = R"(#version 450 core
out float count;
void main() { count = 1.0; }
)";

bool isPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }

}  // namespace

std::unique_ptr<LlvmpipeCoverage> LlvmpipeCoverage::create(int width, int height, int threads,
                                                           std::string& error) {
  if (!isPowerOfTwo(width) || !isPowerOfTwo(height)) {
    error = "the count image's size must be powers of two";
    return nullptr;
  }
  std::unique_ptr<LlvmpipeCoverage> c(new LlvmpipeCoverage());
  c->gl_ = LlvmpipeContext::create(threads, error);
  if (!c->gl_) return nullptr;
  c->width_ = width;
  c->height_ = height;

  glGenRenderbuffers(1, &c->countBuffer_);
  glBindRenderbuffer(GL_RENDERBUFFER, c->countBuffer_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_R32F, width, height);
  glGenFramebuffers(1, &c->framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, c->framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c->countBuffer_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    error = "R32F framebuffer is incomplete";
    return nullptr;
  }
  c->program_ = linkProgram(kVertexShader, kFragmentShader, error);
  if (!error.empty()) return nullptr;
  glUseProgram(c->program_);
  glGenVertexArrays(1, &c->vertexArray_);
  glBindVertexArray(c->vertexArray_);
  glGenBuffers(1, &c->vertexBuffer_);
  glBindBuffer(GL_ARRAY_BUFFER, c->vertexBuffer_);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(glm::vec2), nullptr);
  glEnableVertexAttribArray(0);

  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_MULTISAMPLE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  glClearColor(0, 0, 0, 0);
  error = takeGlError();
  if (!error.empty()) return nullptr;
  return c;
}

LlvmpipeCoverage::~LlvmpipeCoverage() {
  if (!gl_) return;
  glDeleteBuffers(1, &vertexBuffer_);
  glDeleteVertexArrays(1, &vertexArray_);
  glDeleteProgram(program_);
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteRenderbuffers(1, &countBuffer_);
}

// GL's window y points up from the bottom row: y_gl = height - y. With the image a power of two,
// the NDC value (x - w/2) / (w/2) only rescales by a power of two and shifts, so for a grid value
// it is exact, and llvmpipe's ndc * (w/2) + w/2 in float gives x back.
glm::vec2 LlvmpipeCoverage::toNdc(glm::vec2 window) const {
  const double hw = 0.5 * width_, hh = 0.5 * height_;
  return {float((double(window.x) - hw) / hw), float((double(height_) - window.y - hh) / hh)};
}

bool LlvmpipeCoverage::representable(glm::vec2 window) const {
  const glm::vec2 ndc = toNdc(window);
  const float hw = 0.5f * float(width_), hh = 0.5f * float(height_);
  // The float transform, fused or not, must give the point back exactly: it does when both the
  // product and the sum are exact, which these double checks establish.
  const double x = double(ndc.x) * hw + hw, y = double(ndc.y) * hh + hh;
  return double(float(double(ndc.x) * hw)) == double(ndc.x) * hw &&
         double(float(double(ndc.y) * hh)) == double(ndc.y) * hh && double(float(x)) == x &&
         double(float(y)) == y && x == double(window.x) && y == double(height_) - window.y;
}

std::vector<uint32_t> LlvmpipeCoverage::countCoverage(std::span<const glm::vec2> vertices,
                                                      std::string& error) {
  std::vector<glm::vec2> ndc;
  ndc.reserve(vertices.size());
  for (const glm::vec2 v : vertices) {
    if (!representable(v)) {
      error = "vertex (" + std::to_string(v.x) + ", " + std::to_string(v.y) +
              ") does not reach llvmpipe exactly";
      return {};
    }
    ndc.push_back(toNdc(v));
  }
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(ndc.size() * sizeof(glm::vec2)), ndc.data(),
               GL_STREAM_DRAW);
  glClear(GL_COLOR_BUFFER_BIT);
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(ndc.size() / 3 * 3));
  std::vector<float> image(size_t(width_) * size_t(height_));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RED, GL_FLOAT, image.data());
  error = takeGlError();
  std::vector<uint32_t> counts(image.size());
  for (int row = 0; row < height_; ++row)  // GL's row 0 is the bottom one
    for (int x = 0; x < width_; ++x)
      counts[size_t(height_ - 1 - row) * width_ + x] = uint32_t(image[size_t(row) * width_ + x]);
  return counts;
}

}  // namespace rast::peer
