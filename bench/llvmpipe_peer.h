// The peer: Mesa's llvmpipe software rasterizer, driven through a headless EGL context (the
// surfaceless platform) and desktop OpenGL 4.5 core, rendering the workloads of workloads.h into
// an offscreen framebuffer of RGBA8 colour and 24-bit depth.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "scene/mesh.h"

namespace rast::peer {

// Fragments of one frame, counted by occlusion queries: `rasterized` with the depth compare set
// to always, `depthPassed` with the workload's own state.
struct FragmentCounts {
  uint64_t rasterized = 0;
  uint64_t depthPassed = 0;
};

class LlvmpipePeer {
 public:
  // Creates a context with `threads` llvmpipe rasterizer threads and a width x height
  // framebuffer. llvmpipe reads LP_NUM_THREADS when its screen is created, at eglInitialize of a
  // terminated (or new) display, and starts that many threads with the first context; a new
  // context on a live display keeps the old count (measured on Mesa 22.3.6). So this sets it
  // first, and afterwards counts the process's llvmpipe threads to make sure it took. Only one
  // peer may exist at a time (the EGL display is shared by the process). Returns
  // null with `error` set if there is no EGL, no surfaceless platform, no GL 4.5 core context,
  // a renderer other than llvmpipe, or the wrong number of threads.
  static std::unique_ptr<LlvmpipePeer> create(int threads, int width, int height,
                                              std::string& error);
  ~LlvmpipePeer();
  LlvmpipePeer(const LlvmpipePeer&) = delete;
  LlvmpipePeer& operator=(const LlvmpipePeer&) = delete;

  int threads() const;
  const std::string& renderer() const;  // GL_RENDERER

  // What the next frames draw, replacing what was loaded before.
  // W1/W4: positions and normals, W1's shader; colour writes off for W4.
  void loadLitMesh(const Mesh& mesh, const glm::mat4& viewProjection, bool colorWrite);
  // W2/W3: positions in NDC (toNormalizedDeviceCoordinates), constant colour.
  void loadFlatGeometry(std::span<const glm::vec3> ndcPositions,
                        std::span<const uint32_t> indices);

  // One frame: clear colour and depth (1), draw, glFinish.
  void renderFrame();
  // Renders two more frames under occlusion queries.
  FragmentCounts countFragments();

  // The first GL error since the last call, or empty.
  std::string takeGlError();

 private:
  struct Context;
  explicit LlvmpipePeer(std::unique_ptr<Context> context);
  std::unique_ptr<Context> context_;
};

// Threads of this process whose name starts with "llvmpipe-": llvmpipe's rasterizer threads.
int countLlvmpipeThreads();

}  // namespace rast::peer
