// The vertex stage: runs the vertex shader once per unique index of a draw (a post-transform
// cache as large as the vertex buffer, so every repeat of an index is a hit).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

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

// Keeps the first N varyings: the ones the pixel shader reads. Returns false, having shaded
// nothing, when an index is out of range for `vertices` (validateIndices names the first).
template <VertexShader VS, int N = VS::kVaryings>
[[nodiscard]] bool runVertexStage(const VS& shader,
                                  std::span<const typename VS::Vertex> vertices,
                                  std::span<const uint32_t> indices, TransformedVertices<N>& out,
                                  PipelineStatistics& stats) {
  static_assert(N <= VS::kVaryings, "the pixel shader reads more varyings than the vertex shader writes");
  auto shade = [&](size_t from, ShadedVertex<N>& kept) {
    const ShadedVertex<VS::kVaryings> full = shader(vertices[from]);
    // Component by component: a shader that builds its position from parts (a window-space
    // vec3 and w = 1) leaves them in registers, where a whole-vec4 copy made GCC store the parts
    // and load them back as one 16-byte value, a failed store forwarding per vertex (W2 tiny-1:
    // 4 % of the frame).
    for (int c = 0; c < 4; ++c) kept.position[c] = full.position[c];
    for (int k = 0; k < N; ++k) kept.varyings[k] = full.varyings[k];
  };
  // A draw that uses every vertex of its buffer (a mesh, W2's grid) needs no renumbering: the
  // buffer's order serves, the indices are used as they are, and every step runs in parallel.
  // Whether it does is one parallel pass of marks, each thread in an array of its own: marks of
  // several threads in one array made its cache lines travel from core to core (W1 at 2 threads:
  // the vertex stage took 0.73 ms, against 0.53 ms with an array per thread). Bytes, not bits:
  // a bit's read-modify-write made W2 tiny-1's stage 14 % slower.
  using Marks = ScratchVector<uint8_t>;
  tbb::enumerable_thread_specific<Marks> marks(
      [&] { return Marks(vertices.size(), 0, ScratchAllocator<uint8_t>(out.memory)); });
  // The marks pass is also the range check: a branch never taken in a valid draw, where a pass of
  // its own cost a read of every index.
  std::atomic<bool> outOfRange = false;
  forEachChunk(indices.size(), 1 << 16, [&](size_t, size_t begin, size_t end) {
    Marks& used = marks.local();
    // (Held in locals: byte stores may alias the vector's own pointers.)
    uint8_t* const mark = used.data();
    const size_t count = used.size();
    bool bad = false;
    for (size_t i = begin; i < end; ++i) {
      const uint32_t v = indices[i];
      if (v < count) mark[v] = 1;
      else bad = true;
    }
    if (bad) outOfRange = true;
  });
  if (outOfRange) return false;
  Marks* used = nullptr;  // every thread's marks, merged into the first's
  for (Marks& m : marks) {
    if (!used) {
      used = &m;
      continue;
    }
    for (size_t v = 0; v < m.size(); ++v) (*used)[v] |= m[v];
  }
  const bool usesAll = used ? std::find(used->begin(), used->end(), uint8_t{0}) == used->end()
                            : vertices.empty();
  if (usesAll) {
    out.indices = indices;
    out.vertices.resize(vertices.size());
    forEachChunk(vertices.size(), 4096, [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) shade(i, out.vertices[i]);
    });
    stats.inputIndices += indices.size();
    stats.vertexShaderInvocations += vertices.size();
    return true;
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
  return true;
}

}  // namespace rast
