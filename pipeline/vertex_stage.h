// The vertex stage: runs the vertex shader once per unique index of a draw (a post-transform
// cache as large as the vertex buffer, so every repeat of an index is a hit).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/shader.h"
#include "pipeline/statistics.h"

namespace rast {

template <int N>
struct TransformedVertices {
  std::vector<ShadedVertex<N>> vertices;  // in order of first use
  std::vector<uint32_t> indices;          // the draw's indices, renumbered into `vertices`
};

// Indices must already be validated against vertices.size().
template <VertexShader VS, int N = VS::kVaryings>
void runVertexStage(const VS& shader, std::span<const typename VS::Vertex> vertices,
                    std::span<const uint32_t> indices, TransformedVertices<N>& out,
                    PipelineStatistics& stats) {
  static_assert(N <= VS::kVaryings, "the pixel shader reads more varyings than the vertex shader writes");
  constexpr uint32_t kNotShaded = ~uint32_t{0};
  std::vector<uint32_t> slot(vertices.size(), kNotShaded);
  out.vertices.clear();
  out.indices.resize(indices.size());
  for (size_t i = 0; i < indices.size(); ++i) {
    uint32_t& s = slot[indices[i]];
    if (s == kNotShaded) {
      s = uint32_t(out.vertices.size());
      const ShadedVertex<VS::kVaryings> full = shader(vertices[indices[i]]);
      ShadedVertex<N> kept{full.position, {}};
      for (int k = 0; k < N; ++k) kept.varyings[k] = full.varyings[k];
      out.vertices.push_back(kept);
    }
    out.indices[i] = s;
  }
  stats.inputIndices += indices.size();
  stats.vertexShaderInvocations += out.vertices.size();
}

}  // namespace rast
