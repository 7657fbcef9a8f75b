// The front end after the vertex stage: primitive assembly, clip and setup. Turns the draw's
// transformed vertices into set-up triangles in submission order.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "pipeline/clip.h"
#include "pipeline/clip_codes.h"
#include "pipeline/execution.h"
#include "pipeline/setup.h"
#include "pipeline/setup_batch.h"
#include "pipeline/vertex_stage.h"

namespace rast {

// Clips and sets up triangles [begin, end) of the draw, appending to `out` in order.
template <int N>
void clipAndSetup(const TransformedVertices<N>& in, const ScratchVector<VertexClipCodes>& codes,
                  uint32_t begin, uint32_t end, const SetupContext& ctx,
                  const ClipPlanes& planes, ScratchVector<SetupTriangle<N>>& out,
                  ScratchVector<FloatEdges>* floatOut, detail::SetupIsa isa,
                  PipelineStatistics& stats) {
  stats.inputTriangles += end - begin;
  out.reserve(out.size() + (end - begin));
  if (floatOut) floatOut->reserve(floatOut->size() + (end - begin));
  ClipPolygon<N> polygon;
  FloatEdges floatEdges;
  // Unclipped triangles in fixed-point mode are set up several at a time (setup_batch.h); float
  // mode and clipped triangles one at a time.
  SetupBatch<N> batch(ctx, isa);
  // Set up in place in `out`, and taken back when the triangle draws nothing: no copy of each
  // triangle through the stack (1-2 % of setup on W1 and W2).
  auto setUp = [&](const auto& vertices, uint32_t primitiveId) {
    SetupTriangle<N>& triangle = out.emplace_back();
    if (setupTriangle<N>(vertices, ctx, primitiveId, triangle, floatEdges, stats)) {
      if (floatOut) floatOut->push_back(floatEdges);
    } else {
      out.pop_back();
    }
  };
  for (uint32_t t = begin; t < end; ++t) {
    // A mesh's indices jump about its vertices: fetching a later triangle's vertices and codes
    // while this one is set up hides the misses that setup, one triangle at a time, would wait on.
    constexpr uint32_t kAhead = 8;  // 16 measured the same
    if (t + kAhead < end)
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = in.indices[3 * (t + kAhead) + k];
        __builtin_prefetch(&in.vertices[i]);
        __builtin_prefetch(&codes[i]);
      }
    const uint32_t i0 = in.indices[3 * t], i1 = in.indices[3 * t + 1], i2 = in.indices[3 * t + 2];
    const VertexClipCodes &c0 = codes[i0], &c1 = codes[i1], &c2 = codes[i2];
    if (!c0.finite || !c1.finite || !c2.finite) {
      ++stats.clipNonFinite;
      continue;
    }
    if (c0.reject & c1.reject & c2.reject) {
      ++stats.clipTrivialReject;
      continue;
    }
    const std::array<const ShadedVertex<N>*, 3> tri = {&in.vertices[i0], &in.vertices[i1],
                                                       &in.vertices[i2]};
    const unsigned crossed = c0.clip | c1.clip | c2.clip;
    if (!crossed) {
      ++stats.clipOutputTriangles;
      if (floatOut) {
        setUp(tri, t);
      } else {
        batch.add(tri, t);
        if (batch.full()) batch.flush(out, stats);
      }
      continue;
    }
    ++stats.clipClipped;
    // Triangles leave setup in order: the batched ones before this one.
    batch.flush(out, stats);
    clipTriangle(tri, planes, crossed, polygon, &stats);
    // The clipped polygon is convex and keeps the winding: a fan from its first vertex.
    for (int k = 1; k + 1 < polygon.count; ++k) {
      ++stats.clipOutputTriangles;
      const std::array<const ClippedVertex<N>*, 3> part = {
          &polygon.vertices[0], &polygon.vertices[k], &polygon.vertices[k + 1]};
      setUp(part, t);
    }
  }
  batch.flush(out, stats);
}

// The set-up triangles of a draw, in the chunks that made them (one chunk per 4096 input
// triangles), in submission order. They are never concatenated: copying them would double the
// front end's memory traffic, and chunk-sized blocks are reused by the allocator from draw to
// draw where one frame-sized block would be fresh pages (page faults) every time. A triangle is
// named by its chunk and its place in the chunk, packed in 32 bits (TriangleId).
template <int N>
struct SetupTriangles {
  static constexpr size_t kInputChunk = 4096;
  // Clipping makes at most kMaxClipVertices - 2 = 8 triangles of one, so a chunk holds at most
  // 8 * 4096 = 2^15 triangles: 15 bits of local index, 16 of chunk (2^28 input triangles, which
  // validateDraw enforces), leaving bin entries a 32nd bit (kWholeTileBit, bin.h).
  static constexpr int kLocalBits = 15;
  static_assert(kInputChunk * (kMaxClipVertices - 2) <= (size_t{1} << kLocalBits));

  std::vector<ScratchVector<SetupTriangle<N>>> chunks;
  // RasterMode::Float only (empty otherwise): each triangle's float edges, in the same places.
  std::vector<ScratchVector<FloatEdges>> floatChunks;

  static uint32_t id(size_t chunk, size_t local) { return uint32_t(chunk << kLocalBits | local); }
  const SetupTriangle<N>& operator[](uint32_t id) const {
    return chunks[id >> kLocalBits][id & ((uint32_t{1} << kLocalBits) - 1)];
  }
  const FloatEdges& floatEdges(uint32_t id) const {
    return floatChunks[id >> kLocalBits][id & ((uint32_t{1} << kLocalBits) - 1)];
  }
  size_t size() const {
    size_t n = 0;
    for (const auto& c : chunks) n += c.size();
    return n;
  }
};

// The whole front end after the vertex stage, in parallel chunks of triangles. `afterChunk(c)`
// runs in the task that set up chunk c, right after it (binning, while the triangles are in
// that core's cache).
struct NoChunkStep {
  void operator()(size_t) const {}
};
template <int N, class AfterChunk = NoChunkStep>
void clipAndSetupAll(const TransformedVertices<N>& in, const SetupContext& ctx,
                     const ClipPlanes& planes, SetupTriangles<N>& out, PipelineStatistics& stats,
                     AfterChunk&& afterChunk = {}) {
  const ScratchVector<VertexClipCodes> codes = computeClipCodes(in.vertices, planes);
  const detail::SetupIsa isa = detail::bestSetupIsa();
  constexpr size_t kChunk = SetupTriangles<N>::kInputChunk;
  const size_t triangleCount = in.indices.size() / 3;
  const size_t chunks = chunkCount(triangleCount, kChunk);
  const ScratchAllocator<std::byte> memory(in.memory);
  out.chunks.resize(chunks, ScratchVector<SetupTriangle<N>>(memory));
  const bool floatMode = ctx.rasterMode == RasterMode::Float;
  out.floatChunks.resize(floatMode ? chunks : 0, ScratchVector<FloatEdges>(memory));
  std::vector<PipelineStatistics> partStats(chunks);
  forEachChunk(triangleCount, kChunk, [&](size_t c, size_t begin, size_t end) {
    clipAndSetup(in, codes, uint32_t(begin), uint32_t(end), ctx, planes, out.chunks[c],
                 floatMode ? &out.floatChunks[c] : nullptr, isa, partStats[c]);
    afterChunk(c);
  });
  for (const PipelineStatistics& s : partStats) stats += s;
}

}  // namespace rast
