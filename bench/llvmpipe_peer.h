// The peer: Mesa's llvmpipe software rasterizer, driven through a headless EGL context
// (peer/llvmpipe_context.h), rendering the workloads of workloads.h into an offscreen framebuffer
// of RGBA8 colour and 24-bit depth.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "peer/llvmpipe_context.h"
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
  // Creates a context with `threads` llvmpipe rasterizer threads (LlvmpipeContext::create: only
  // one may exist at a time) and a width x height framebuffer. Returns null with `error` set if
  // either cannot be made.
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

}  // namespace rast::peer
