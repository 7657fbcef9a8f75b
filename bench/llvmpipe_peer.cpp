#include "bench/llvmpipe_peer.h"

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <thread>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
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

bool hasExtension(const char* list, std::string_view name) {
  if (!list) return false;
  for (std::string_view rest = list; !rest.empty();) {
    const size_t end = rest.find(' ');
    if (rest.substr(0, end) == name) return true;
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  return false;
}

std::string hex(unsigned value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04x", value);
  return text;
}

std::string eglErrorText(const char* what) {
  return std::string(what) + " failed (EGL error " + hex(unsigned(eglGetError())) + ")";
}

GLuint compileShader(GLenum kind, const char* source, std::string& error) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    error = std::string("GLSL compile error: ") + log;
  }
  return shader;
}

GLuint linkProgram(const char* vertexSource, const char* fragmentSource, std::string& error) {
  const GLuint vs = compileShader(GL_VERTEX_SHADER, vertexSource, error);
  const GLuint fs = compileShader(GL_FRAGMENT_SHADER, fragmentSource, error);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok && error.empty()) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    error = std::string("GLSL link error: ") + log;
  }
  return program;
}

}  // namespace

int countLlvmpipeThreads() {
  int count = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    if (std::getline(comm, name) && name.starts_with("llvmpipe-")) ++count;
  }
  return count;
}

namespace {

// Waits (up to a second) until `expected` llvmpipe threads are seen and returns the count last
// seen: a new thread names itself only once it runs, and a joined thread of the previous display
// can linger in /proc for a moment, both easily seen on a loaded machine.
int awaitLlvmpipeThreads(int expected) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  int running = countLlvmpipeThreads();
  while (running != expected && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    running = countLlvmpipeThreads();
  }
  return running;
}

}  // namespace

struct LlvmpipePeer::Context {
  int threads = 0;
  int width = 0, height = 0;
  std::string renderer;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
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
    if (context != EGL_NO_CONTEXT) {
      deleteGeometry();
      glDeleteProgram(litProgram);
      glDeleteProgram(flatProgram);
      glDeleteFramebuffers(1, &framebuffer);
      glDeleteRenderbuffers(1, &colorBuffer);
      glDeleteRenderbuffers(1, &depthBuffer);
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
      context = EGL_NO_CONTEXT;
    }
    // Terminating lets llvmpipe destroy its screen and join its threads, so the next
    // eglInitialize creates a new screen that reads LP_NUM_THREADS again.
    if (display != EGL_NO_DISPLAY) eglTerminate(display);
    display = EGL_NO_DISPLAY;
    eglReleaseThread();
  }

  std::string initialize() {
    // The environment is llvmpipe's only configuration interface; these must be set before
    // eglInitialize. LIBGL_ALWAYS_SOFTWARE keeps Mesa from a GPU's render node, GALLIUM_DRIVER
    // picks llvmpipe over softpipe.
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    setenv("GALLIUM_DRIVER", "llvmpipe", 1);
    setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);

    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExtensions, "EGL_EXT_platform_base") ||
        !hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
      return "EGL lacks EGL_EXT_platform_base or EGL_MESA_platform_surfaceless (is Mesa's EGL "
             "installed, libegl-mesa0?)";
    const auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) return "eglGetPlatformDisplayEXT not found";
    display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) return eglErrorText("eglGetPlatformDisplayEXT(surfaceless)");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      display = EGL_NO_DISPLAY;
      return eglErrorText("eglInitialize");
    }
    const char* displayExtensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!hasExtension(displayExtensions, "EGL_KHR_surfaceless_context") ||
        !hasExtension(displayExtensions, "EGL_KHR_no_config_context"))
      return "EGL display lacks EGL_KHR_surfaceless_context or EGL_KHR_no_config_context";
    if (!eglBindAPI(EGL_OPENGL_API)) return eglErrorText("eglBindAPI(OpenGL)");
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                        EGL_CONTEXT_MINOR_VERSION, 5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) return eglErrorText("eglCreateContext(OpenGL 4.5 core)");
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      return eglErrorText("eglMakeCurrent");

    const auto* rendererName = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    renderer = rendererName ? rendererName : "";
    if (renderer.find("llvmpipe") == std::string::npos)
      return "GL_RENDERER is \"" + renderer + "\", not llvmpipe";
    if (const int running = awaitLlvmpipeThreads(threads); running != threads)
      return "LP_NUM_THREADS=" + std::to_string(threads) + " but " + std::to_string(running) +
             " llvmpipe threads are running";

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

    std::string error;
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
const std::string& LlvmpipePeer::renderer() const { return context_->renderer; }

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

std::string LlvmpipePeer::takeGlError() {
  const GLenum e = glGetError();
  return e == GL_NO_ERROR ? std::string() : "GL error " + hex(unsigned(e));
}

}  // namespace rast::peer
