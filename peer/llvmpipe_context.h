// Mesa's llvmpipe software rasterizer behind a headless EGL context (the surfaceless platform)
// with desktop OpenGL 4.5 core: the context alone, for the peer benchmarks (bench/) and the
// conformance tests (tests/llvmpipe_conformance_test.cpp), each of which adds its own objects.
#pragma once

#include <memory>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

namespace rast::peer {

class LlvmpipeContext {
 public:
  // Creates a context with `threads` llvmpipe rasterizer threads and makes it current on the
  // calling thread. llvmpipe reads LP_NUM_THREADS when its screen is created, at eglInitialize of
  // a terminated (or new) display, and starts that many threads with the first context; a new
  // context on a live display keeps the old count (measured on Mesa 22.3.6). So this sets it
  // first, and afterwards counts the process's llvmpipe threads to make sure it took. Only one
  // context may exist at a time (the EGL display is shared by the process). Returns null with
  // `error` set if there is no EGL, no surfaceless platform, no GL 4.5 core context, a renderer
  // other than llvmpipe, or the wrong number of threads.
  static std::unique_ptr<LlvmpipeContext> create(int threads, std::string& error);
  // Destroys the context and terminates the display (so the next create reads LP_NUM_THREADS
  // again). Delete the context's GL objects first: the context is current until then.
  ~LlvmpipeContext();
  LlvmpipeContext(const LlvmpipeContext&) = delete;
  LlvmpipeContext& operator=(const LlvmpipeContext&) = delete;

  int threads() const { return threads_; }
  const std::string& renderer() const { return renderer_; }  // GL_RENDERER

 private:
  LlvmpipeContext() = default;
  std::string initialize();
  void destroy();

  int threads_ = 0;
  std::string renderer_;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

// Threads of this process whose name starts with "llvmpipe-": llvmpipe's rasterizer threads.
int countLlvmpipeThreads();

// A program from vertex and fragment shader source; on a compile or link error, `error` holds
// the log (and the returned program is unusable).
GLuint linkProgram(const char* vertexSource, const char* fragmentSource, std::string& error);

// "GL error 0x0502" for the first GL error since the last call, or empty.
std::string takeGlError();

// Four hexadecimal digits, as GL and EGL error codes are written.
std::string hex(unsigned value);

}  // namespace rast::peer
