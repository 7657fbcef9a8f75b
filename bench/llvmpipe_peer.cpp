#include "bench/llvmpipe_peer.h"

#include <cstddef>

#include <glm/gtc/type_ptr.hpp>

#include "bench/workloads.h"

namespace rast::peer {
namespace {

constexpr const char* kLitVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 viewProjection;
out vec3 worldNormal;
void main() {
  worldNormal = normal;
  gl_Position = viewProjection * vec4(position, 1.0);
}
)";

// W1's pixel shader, as W1LambertShader (shaders_cpp/w1_lambert.h).
constexpr const char* kLitFragmentShader = R"(#version 450 core
in vec3 worldNormal;
out vec4 color;
const vec3 lightDirection = normalize(vec3(0.35, 0.55, 0.76));
void main() {
  vec3 n = normalize(worldNormal);
  color = vec4(0.08 + max(dot(n, lightDirection), 0.0) * vec3(0.85, 0.80, 0.70), 1.0);
}
)";

constexpr const char* kFlatVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
void main() { gl_Position = vec4(position, 1.0); }
)";

constexpr const char* kFlatFragmentShader = R"(#version 450 core
uniform vec4 flatColor;
out vec4 color;
void main() { color = flatColor; }
)";

}  // namespace

struct LlvmpipePeer::Context {
  int threads = 0;
  int width = 0, height = 0;
  std::unique_ptr<LlvmpipeContext> gl;
  GLuint framebuffer = 0, colorBuffer = 0, depthBuffer = 0;
  GLuint litProgram = 0, flatProgram = 0;
  GLint viewProjectionLocation = -1, flatColorLocation = -1;
  // The loaded geometry.
  GLuint vertexArray = 0, vertexBuffer = 0, indexBuffer = 0;
  GLsizei indexCount = 0;
  bool colorWrite = true;

  void deleteGeometry() {
    glDeleteVertexArrays(1, &vertexArray);
    glDeleteBuffers(1, &vertexBuffer);
    glDeleteBuffers(1, &indexBuffer);
    vertexArray = vertexBuffer = indexBuffer = 0;
    indexCount = 0;
  }

  // Starts a new vertex array with `vertexBytes` of vertices and the indices.
  void uploadGeometry(const void* vertices, size_t vertexBytes,
                      std::span<const uint32_t> indices) {
    deleteGeometry();
    glGenVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    glGenBuffers(1, &vertexBuffer);
    glBindBuffer(GL_ARRAY_BUFFER, vertexBuffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertexBytes), vertices, GL_STATIC_DRAW);
    glGenBuffers(1, &indexBuffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size_bytes()), indices.data(),
                 GL_STATIC_DRAW);
    indexCount = GLsizei(indices.size());
  }

  void clearAndDraw() {
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);  // glClear obeys the colour mask
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glColorMask(colorWrite, colorWrite, colorWrite, colorWrite);
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
  }

  uint64_t samplesPassedByDraw() {
    GLuint query = 0;
    glGenQueries(1, &query);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glColorMask(colorWrite, colorWrite, colorWrite, colorWrite);
    glBeginQuery(GL_SAMPLES_PASSED, query);
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 samples = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &samples);
    glDeleteQueries(1, &query);
    return samples;
  }

  void destroy() {
    if (!gl) return;
    deleteGeometry();
    glDeleteProgram(litProgram);
    glDeleteProgram(flatProgram);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteRenderbuffers(1, &colorBuffer);
    glDeleteRenderbuffers(1, &depthBuffer);
    gl.reset();
  }

  std::string initialize() {
    std::string error;
    gl = LlvmpipeContext::create(threads, error);
    if (!gl) return error;

    glGenRenderbuffers(1, &colorBuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, colorBuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenRenderbuffers(1, &depthBuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, depthBuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      return "RGBA8 + DEPTH_COMPONENT24 framebuffer is incomplete";

    litProgram = linkProgram(kLitVertexShader, kLitFragmentShader, error);
    flatProgram = linkProgram(kFlatVertexShader, kFlatFragmentShader, error);
    if (!error.empty()) return error;
    viewProjectionLocation = glGetUniformLocation(litProgram, "viewProjection");
    flatColorLocation = glGetUniformLocation(flatProgram, "flatColor");

    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    const glm::vec4 c = workloads::kClearColor;
    glClearColor(c.r, c.g, c.b, c.a);
    glClearDepth(workloads::kClearDepth);
    if (const GLenum e = glGetError(); e != GL_NO_ERROR)
      return "GL error " + hex(unsigned(e)) + " while setting up";
    return {};
  }
};

std::unique_ptr<LlvmpipePeer> LlvmpipePeer::create(int threads, int width, int height,
                                                   std::string& error) {
  auto context = std::make_unique<Context>();
  context->threads = threads;
  context->width = width;
  context->height = height;
  error = context->initialize();
  if (!error.empty()) {
    context->destroy();
    return nullptr;
  }
  return std::unique_ptr<LlvmpipePeer>(new LlvmpipePeer(std::move(context)));
}

LlvmpipePeer::LlvmpipePeer(std::unique_ptr<Context> context) : context_(std::move(context)) {}

LlvmpipePeer::~LlvmpipePeer() { context_->destroy(); }

int LlvmpipePeer::threads() const { return context_->threads; }
const std::string& LlvmpipePeer::renderer() const { return context_->gl->renderer(); }

void LlvmpipePeer::loadLitMesh(const Mesh& mesh, const glm::mat4& viewProjection,
                               bool colorWrite) {
  Context& c = *context_;
  c.uploadGeometry(mesh.vertices.data(), mesh.vertices.size() * sizeof(MeshVertex), mesh.indices);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                        reinterpret_cast<const void*>(offsetof(MeshVertex, position)));
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                        reinterpret_cast<const void*>(offsetof(MeshVertex, normal)));
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  glUseProgram(c.litProgram);
  glUniformMatrix4fv(c.viewProjectionLocation, 1, GL_FALSE, glm::value_ptr(viewProjection));
  c.colorWrite = colorWrite;
}

void LlvmpipePeer::loadFlatGeometry(std::span<const glm::vec3> ndcPositions,
                                    std::span<const uint32_t> indices) {
  Context& c = *context_;
  c.uploadGeometry(ndcPositions.data(), ndcPositions.size_bytes(), indices);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glEnableVertexAttribArray(0);
  glUseProgram(c.flatProgram);
  const glm::vec4 color = workloads::kFlatColor;
  glUniform4f(c.flatColorLocation, color.r, color.g, color.b, color.a);
  c.colorWrite = true;
}

void LlvmpipePeer::renderFrame() {
  context_->clearAndDraw();
  glFinish();
}

FragmentCounts LlvmpipePeer::countFragments() {
  FragmentCounts counts;
  counts.depthPassed = context_->samplesPassedByDraw();
  glDepthFunc(GL_ALWAYS);
  counts.rasterized = context_->samplesPassedByDraw();
  glDepthFunc(GL_LESS);
  return counts;
}

std::string LlvmpipePeer::takeGlError() { return peer::takeGlError(); }

}  // namespace rast::peer
