// The standard benchmark workloads W1-W4 (../shared/design/workloads.md): their geometry, in the
// form both our pipeline and the peer (llvmpipe_peer.h) take, and one frame of each on our
// pipeline. Both renderers get the same positions, so they draw the same pixels.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "pipeline/execution.h"
#include "pipeline/framebuffer.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "pipeline/status.h"
#include "scene/mesh.h"
#include "shaders_cpp/window_space.h"

namespace rast::workloads {

inline constexpr int kFrameWidth = 1920;
inline constexpr int kFrameHeight = 1080;

// Every frame starts from these.
inline constexpr glm::vec4 kClearColor{0.0f, 0.0f, 0.0f, 1.0f};
inline constexpr float kClearDepth = 1.0f;
// The constant colour of W2 and W3.
inline constexpr glm::vec4 kFlatColor{0.9f, 0.6f, 0.2f, 1.0f};

// The state every workload draws with: a full-frame viewport, depth compare less with writes,
// no culling, and the peer's 8 subpixel bits (16.8), so that our fragment counts can equal its
// counts exactly.
PipelineState workloadState(int width, int height, PositionSpace space);

// ---- W1 (and W4): the Stanford bunny, lit.

struct LitMeshScene {
  Mesh mesh;                 // positions and area-weighted vertex normals
  glm::mat4 viewProjection;  // W1's camera (frameMesh), aspect width / height
};

// Loads the mesh (../shared/data/meshes/bunny.obj for W1) and frames it for a width x height frame.
Status loadLitMeshScene(const std::string& objPath, int width, int height, LitMeshScene& out);

// ---- W2 and W3: flat-shaded geometry given in window coordinates.

// Window coordinates as our pipeline's PositionSpace::Window takes them: x, y in pixels with y
// down, z the depth in [0, 1].
struct WindowGeometry {
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;  // three per triangle, one draw

  size_t triangleCount() const { return indices.size() / 3; }
};

// The same positions in OpenGL normalised device coordinates for a width x height viewport with
// the default depth range: the peer's viewport transform maps them back to the same pixels (its
// window y points up, ours down, so y' = height - y) and the same depths.
std::vector<glm::vec3> toNormalizedDeviceCoordinates(const WindowGeometry& geometry, int width,
                                                     int height);

// W2: a screen grid of right triangles of area `area` px² (two per square cell of side
// sqrt(2 area)), shared vertices, covering the frame.
struct TriangleGridSize {
  double cellSide = 0;
  int cols = 0, rows = 0;

  int triangleCount() const { return 2 * cols * rows; }
};
TriangleGridSize triangleGridSize(double area, int width, int height);

inline constexpr std::array<int, 4> kTinyTriangleAreas{1, 10, 100, 1000};
inline constexpr float kTinyTriangleDepth = 0.5f;

// Vertex (i, j) at (i s, j s); cell (i, j) split into (a, b, d) and (a, d, c), a = (i, j),
// b = (i+1, j), c = (i, j+1), d = (i+1, j+1).
WindowGeometry triangleGrid(double area, int width, int height, float depth);

// W3: 16 full-frame layers, layer l at NDC z = -0.9 + 1.8 l / 15 (layer 0 nearest).
inline constexpr int kOverdrawLayers = 16;
// The tessellated variant's triangle area: each layer is then a W2 tiny-1000 grid.
inline constexpr double kTessellatedLayerTriangleArea = 1000.0;

enum class LayerOrder { FrontToBack, BackToFront };
enum class LayerShape { Quad, Tessellated };

float overdrawLayerNdcZ(int layer);
// All layers in one draw, in `order`: two triangles per layer, or a tiny-1000 grid per layer.
WindowGeometry overdrawLayers(int width, int height, LayerOrder order, LayerShape shape);

// ---- One frame on our pipeline: clear colour and depth (the draw's load op,
// PipelineState::clear), draw; the frame's counters in `stats`.
// `fb` gives the frame size; the geometry must have been made for that size.

Status renderW1Frame(Framebuffer& fb, const LitMeshScene& scene, PipelineStatistics& stats,
                     const ExecutionOptions& exec = {});
Status renderW2Frame(Framebuffer& fb, const WindowGeometry& grid, PipelineStatistics& stats,
                     const ExecutionOptions& exec = {});
Status renderW3Frame(Framebuffer& fb, const WindowGeometry& layers, PipelineStatistics& stats,
                     const ExecutionOptions& exec = {});
// W1 with colour writes off.
Status renderW4Frame(Framebuffer& fb, const LitMeshScene& scene, PipelineStatistics& stats,
                     const ExecutionOptions& exec = {});

// The draw of W1 alone (no clear) with any state (clip space), for the precision laboratory's
// modes.
Status drawLitMesh(Framebuffer& fb, const PipelineState& state, const LitMeshScene& scene,
                   PipelineStatistics& stats, const ExecutionOptions& exec = {});

// The draw of W2 and W3 alone (no clear) with any state, for checks with other depth compares.
Status drawFlatGeometry(Framebuffer& fb, const PipelineState& state,
                        const WindowGeometry& geometry, PipelineStatistics& stats,
                        const ExecutionOptions& exec = {});

}  // namespace rast::workloads
