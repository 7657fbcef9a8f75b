#include "bench/workloads.h"

#include <cmath>

#include "pipeline/draw.h"
#include "scene/camera.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/w1_lambert.h"

namespace rast::workloads {
namespace {

// Window depth of an NDC z under the default depth range [0, 1].
float windowDepth(float ndcZ) { return 0.5f * ndcZ + 0.5f; }

// Appends a triangle grid's vertices and indices to `out`.
void appendTriangleGrid(const TriangleGridSize& size, float depth, WindowGeometry& out) {
  const uint32_t base = uint32_t(out.vertices.size());
  const int verticesPerRow = size.cols + 1;
  for (int j = 0; j <= size.rows; ++j)
    for (int i = 0; i <= size.cols; ++i)
      out.vertices.push_back({{float(i * size.cellSide), float(j * size.cellSide), depth}});
  auto vertex = [&](int i, int j) { return base + uint32_t(j * verticesPerRow + i); };
  for (int j = 0; j < size.rows; ++j)
    for (int i = 0; i < size.cols; ++i) {
      const uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i, j + 1),
                     d = vertex(i + 1, j + 1);
      out.indices.insert(out.indices.end(), {a, b, d, a, d, c});
    }
}

void appendQuad(int width, int height, float depth, WindowGeometry& out) {
  const uint32_t base = uint32_t(out.vertices.size());
  const float w = float(width), h = float(height);
  for (glm::vec2 p : {glm::vec2(0, 0), glm::vec2(w, 0), glm::vec2(w, h), glm::vec2(0, h)})
    out.vertices.push_back({{p.x, p.y, depth}});
  out.indices.insert(out.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

Status renderLitMeshFrame(Framebuffer& fb, const LitMeshScene& scene, bool colorWrite,
                          PipelineStatistics& stats, const ExecutionOptions& exec) {
  PipelineState state = workloadState(fb.width(), fb.height(), PositionSpace::Clip);
  state.colorWrite = colorWrite;
  state.clear = ClearValues{kClearColor, kClearDepth};  // the frame's clear, as the draw's load op
  return drawLitMesh(fb, state, scene, stats, exec);
}

Status renderFlatFrame(Framebuffer& fb, const WindowGeometry& geometry,
                       PipelineStatistics& stats, const ExecutionOptions& exec) {
  PipelineState state = workloadState(fb.width(), fb.height(), PositionSpace::Window);
  state.clear = ClearValues{kClearColor, kClearDepth};
  return drawFlatGeometry(fb, state, geometry, stats, exec);
}

}  // namespace

PipelineState workloadState(int width, int height, PositionSpace space) {
  PipelineState state;
  state.viewport = {0, 0, width, height};
  state.positionSpace = space;
  state.format = FixedPointFormat::d16_8();
  state.cullMode = CullMode::None;
  state.depth.compare = CompareOp::Less;
  state.depth.write = true;
  return state;
}

Status loadLitMeshScene(const std::string& objPath, int width, int height, LitMeshScene& out) {
  if (Status s = loadObj(objPath, out.mesh); !s) return s;
  computeVertexNormals(out.mesh);  // loadObj does too; W1 defines them, so say it here
  out.viewProjection = frameMesh(out.mesh).viewProjection(float(width) / float(height));
  return Status::ok();
}

std::vector<glm::vec3> toNormalizedDeviceCoordinates(const WindowGeometry& geometry, int width,
                                                     int height) {
  std::vector<glm::vec3> ndc;
  ndc.reserve(geometry.vertices.size());
  for (const WindowVertex& v : geometry.vertices) {
    const glm::vec3 p = v.position;
    ndc.push_back({2.0f * p.x / float(width) - 1.0f, 1.0f - 2.0f * p.y / float(height),
                   2.0f * p.z - 1.0f});
  }
  return ndc;
}

TriangleGridSize triangleGridSize(double area, int width, int height) {
  TriangleGridSize size;
  size.cellSide = std::sqrt(2.0 * area);
  size.cols = int(std::ceil(width / size.cellSide));
  size.rows = int(std::ceil(height / size.cellSide));
  return size;
}

WindowGeometry triangleGrid(double area, int width, int height, float depth) {
  WindowGeometry grid;
  appendTriangleGrid(triangleGridSize(area, width, height), depth, grid);
  return grid;
}

float overdrawLayerNdcZ(int layer) {
  return -0.9f + 1.8f * float(layer) / float(kOverdrawLayers - 1);
}

WindowGeometry overdrawLayers(int width, int height, LayerOrder order, LayerShape shape) {
  WindowGeometry layers;
  const TriangleGridSize grid = triangleGridSize(kTessellatedLayerTriangleArea, width, height);
  for (int k = 0; k < kOverdrawLayers; ++k) {
    const int layer = order == LayerOrder::FrontToBack ? k : kOverdrawLayers - 1 - k;
    const float depth = windowDepth(overdrawLayerNdcZ(layer));
    if (shape == LayerShape::Quad) appendQuad(width, height, depth, layers);
    else appendTriangleGrid(grid, depth, layers);
  }
  return layers;
}

Status drawLitMesh(Framebuffer& fb, const PipelineState& state, const LitMeshScene& scene,
                   PipelineStatistics& stats, const ExecutionOptions& exec) {
  const WorldNormalVertexShader vs{glm::mat4(1.0f), scene.viewProjection};
  const W1LambertShader ps;
  return draw(fb, state,
              DrawCall<WorldNormalVertexShader, W1LambertShader>{scene.mesh.vertices,
                                                                 scene.mesh.indices, vs, ps},
              stats, exec);
}

Status drawFlatGeometry(Framebuffer& fb, const PipelineState& state,
                        const WindowGeometry& geometry, PipelineStatistics& stats,
                        const ExecutionOptions& exec) {
  const WindowSpaceVertexShader vs;
  const ConstantColorShader ps{kFlatColor};
  return draw(fb, state,
              DrawCall<WindowSpaceVertexShader, ConstantColorShader>{geometry.vertices,
                                                                     geometry.indices, vs, ps},
              stats, exec);
}

Status renderW1Frame(Framebuffer& fb, const LitMeshScene& scene, PipelineStatistics& stats,
                     const ExecutionOptions& exec) {
  return renderLitMeshFrame(fb, scene, true, stats, exec);
}

Status renderW2Frame(Framebuffer& fb, const WindowGeometry& grid, PipelineStatistics& stats,
                     const ExecutionOptions& exec) {
  return renderFlatFrame(fb, grid, stats, exec);
}

Status renderW3Frame(Framebuffer& fb, const WindowGeometry& layers, PipelineStatistics& stats,
                     const ExecutionOptions& exec) {
  return renderFlatFrame(fb, layers, stats, exec);
}

Status renderW4Frame(Framebuffer& fb, const LitMeshScene& scene, PipelineStatistics& stats,
                     const ExecutionOptions& exec) {
  return renderLitMeshFrame(fb, scene, false, stats, exec);
}

}  // namespace rast::workloads
