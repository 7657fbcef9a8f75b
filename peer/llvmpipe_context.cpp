#include "peer/llvmpipe_context.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <thread>

#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace rast::peer {
namespace {

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

std::string hex(unsigned value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04x", value);
  return text;
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

std::string takeGlError() {
  const GLenum e = glGetError();
  return e == GL_NO_ERROR ? std::string() : "GL error " + hex(unsigned(e));
}

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

std::unique_ptr<LlvmpipeContext> LlvmpipeContext::create(int threads, std::string& error) {
  std::unique_ptr<LlvmpipeContext> c(new LlvmpipeContext());
  c->threads_ = threads;
  error = c->initialize();
  if (!error.empty()) return nullptr;  // the destructor cleans up what was made
  return c;
}

LlvmpipeContext::~LlvmpipeContext() { destroy(); }

void LlvmpipeContext::destroy() {
  const EGLDisplay display = display_;
  if (context_) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context_);
    context_ = nullptr;
  }
  // Terminating lets llvmpipe destroy its screen and join its threads, so the next
  // eglInitialize creates a new screen that reads LP_NUM_THREADS again.
  if (display) eglTerminate(display);
  display_ = nullptr;
  eglReleaseThread();
}

std::string LlvmpipeContext::initialize() {
  // The environment is llvmpipe's only configuration interface; these must be set before
  // eglInitialize. LIBGL_ALWAYS_SOFTWARE keeps Mesa from a GPU's render node, GALLIUM_DRIVER
  // picks llvmpipe over softpipe.
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  setenv("LP_NUM_THREADS", std::to_string(threads_).c_str(), 1);

  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(clientExtensions, "EGL_EXT_platform_base") ||
      !hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
    return "EGL lacks EGL_EXT_platform_base or EGL_MESA_platform_surfaceless (is Mesa's EGL "
           "installed, libegl-mesa0?)";
  const auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) return "eglGetPlatformDisplayEXT not found";
  const EGLDisplay display =
      getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) return eglErrorText("eglGetPlatformDisplayEXT(surfaceless)");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) return eglErrorText("eglInitialize");
  display_ = display;
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
  const EGLContext context =
      eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, contextAttributes);
  if (context == EGL_NO_CONTEXT) return eglErrorText("eglCreateContext(OpenGL 4.5 core)");
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
    return eglErrorText("eglMakeCurrent");

  const auto* rendererName = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  renderer_ = rendererName ? rendererName : "";
  if (renderer_.find("llvmpipe") == std::string::npos)
    return "GL_RENDERER is \"" + renderer_ + "\", not llvmpipe";
  if (const int running = awaitLlvmpipeThreads(threads_); running != threads_)
    return "LP_NUM_THREADS=" + std::to_string(threads_) + " but " + std::to_string(running) +
           " llvmpipe threads are running";
  return {};
}

}  // namespace rast::peer
