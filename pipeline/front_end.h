// The front end after the vertex stage: primitive assembly, clip and setup. Turns the draw's
// transformed vertices into set-up triangles in submission order.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "pipeline/clip.h"
#include "pipeline/setup.h"
#include "pipeline/vertex_stage.h"

namespace rast {

template <int N>
void clipAndSetup(const TransformedVertices<N>& in, const SetupContext& ctx,
                  const ClipPlanes& planes, std::vector<SetupTriangle<N>>& out,
                  PipelineStatistics& stats) {
  // Per vertex, once: finite or not, and which planes it is outside of.
  struct VertexCodes {
    bool finite;
    unsigned reject;
    unsigned clip;
  };
  std::vector<VertexCodes> codes(in.vertices.size());
  for (size_t i = 0; i < in.vertices.size(); ++i) {
    const glm::vec4& p = in.vertices[i].position;
    const bool finite =
        std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
    codes[i] = {finite, finite ? outsideMask(planes.reject, p) : 0u,
                finite ? outsideMask(planes.clip, p) : 0u};
  }

  const uint32_t triangleCount = uint32_t(in.indices.size() / 3);
  stats.inputTriangles += triangleCount;
  out.reserve(out.size() + triangleCount);
  ClipPolygon<N> polygon;
  SetupTriangle<N> triangle;
  for (uint32_t t = 0; t < triangleCount; ++t) {
    const uint32_t i0 = in.indices[3 * t], i1 = in.indices[3 * t + 1], i2 = in.indices[3 * t + 2];
    const VertexCodes &c0 = codes[i0], &c1 = codes[i1], &c2 = codes[i2];
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
      if (setupTriangle(tri, ctx, t, triangle, stats)) out.push_back(triangle);
      continue;
    }
    ++stats.clipClipped;
    clipTriangle(tri, planes, crossed, polygon);
    // The clipped polygon is convex and keeps the winding: a fan from its first vertex.
    for (int k = 1; k + 1 < polygon.count; ++k) {
      ++stats.clipOutputTriangles;
      const std::array<const ShadedVertex<N>*, 3> part = {
          &polygon.vertices[0], &polygon.vertices[k], &polygon.vertices[k + 1]};
      if (setupTriangle(part, ctx, t, triangle, stats)) out.push_back(triangle);
    }
  }
}

}  // namespace rast
