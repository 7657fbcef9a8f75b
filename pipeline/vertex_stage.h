// The vertex stage: runs the vertex shader once per unique index of a draw (a post-transform
// cache as large as the vertex buffer, so every repeat of an index is a hit).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/execution.h"
#include "pipeline/shader.h"
#include "pipeline/statistics.h"

namespace rast {

template <int N>
struct TransformedVertices {
  // `memory`: where this and everything the front end derives from it is allocated.
  explicit TransformedVertices(ScratchMemory* memory = nullptr)
      : memory(memory),
        vertices(ScratchAllocator<ShadedVertex<N>>(memory)),
        renumbered(ScratchAllocator<uint32_t>(memory)) {}

  ScratchMemory* memory;
  // In the buffer's order when the draw uses every vertex, else in order of first use.
  ScratchVector<ShadedVertex<N>> vertices;
  // The draw's indices into `vertices`: the caller's own when the buffer's order serves (they
  // outlive the draw), else `renumbered`.
  std::span<const uint32_t> indices;
  ScratchVector<uint32_t> renumbered;
};

// Indices must already be validated against vertices.size(). Keeps the first N varyings: the
// ones the pixel shader reads.
template <VertexShader VS, int N = VS::kVaryings>
void runVertexStage(const VS& shader, std::span<const typename VS::Vertex> vertices,
                    std::span<const uint32_t> indices, TransformedVertices<N>& out,
                    PipelineStatistics& stats) {
  static_assert(N <= VS::kVaryings, "the pixel shader reads more varyings than the vertex shader writes");
  auto shade = [&](size_t from, ShadedVertex<N>& kept) {
    const ShadedVertex<VS::kVaryings> full = shader(vertices[from]);
    kept.position = full.position;
    for (int k = 0; k < N; ++k) kept.varyings[k] = full.varyings[k];
  };
  // A draw that uses every vertex of its buffer (a mesh, W2's grid) needs no renumbering: the
  // buffer's order serves, the indices are used as they are, and every step runs in parallel.
  // Whether it does is one parallel pass of marks (idempotent stores of 1, atomic so that two
  // threads marking one vertex do not race).
  ScratchVector<uint8_t> used(vertices.size(), 0, ScratchAllocator<uint8_t>(out.memory));
  forEachChunk(indices.size(), 1 << 16, [&](size_t, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      std::atomic_ref<uint8_t>(used[indices[i]]).store(1, std::memory_order_relaxed);
  });
  if (std::find(used.begin(), used.end(), uint8_t{0}) == used.end()) {
    out.indices = indices;
    out.vertices.resize(vertices.size());
    forEachChunk(vertices.size(), 4096, [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) shade(i, out.vertices[i]);
    });
    stats.inputIndices += indices.size();
    stats.vertexShaderInvocations += vertices.size();
    return;
  }
  // Otherwise only the vertices used are shaded, numbered in order of first use: sequential and
  // cheap; shading is not.
  constexpr uint32_t kNotSeen = ~uint32_t{0};
  ScratchVector<uint32_t> slot(vertices.size(), kNotSeen, ScratchAllocator<uint32_t>(out.memory));
  ScratchVector<uint32_t> unique(ScratchAllocator<uint32_t>(out.memory));
  out.renumbered.resize(indices.size());
  for (size_t i = 0; i < indices.size(); ++i) {
    uint32_t& s = slot[indices[i]];
    if (s == kNotSeen) {
      s = uint32_t(unique.size());
      unique.push_back(indices[i]);
    }
    out.renumbered[i] = s;
  }
  out.indices = out.renumbered;
  out.vertices.resize(unique.size());
  forEachChunk(unique.size(), 4096, [&](size_t, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) shade(unique[i], out.vertices[i]);
  });
  stats.inputIndices += indices.size();
  stats.vertexShaderInvocations += unique.size();
}

}  // namespace rast
