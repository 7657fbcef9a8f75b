// Clipping in homogeneous space (Sutherland-Hodgman), against the planes of ClipPlanes::clip.
//
// Watertightness across clipped edges: the point where an edge crosses a plane is computed from
// the edge's endpoints in a canonical order (lexicographically smaller position first), so two
// triangles sharing an edge produce bit-identical new vertices and stay crack-free after snapping.
#pragma once

#include <array>
#include <cstring>

#include "pipeline/shader.h"
#include "pipeline/viewport.h"

namespace rast {

inline constexpr int kMaxClipVertices = 3 + ClipPlanes::kClipPlaneCount;

template <int N>
struct ClipPolygon {
  std::array<ShadedVertex<N>, kMaxClipVertices> vertices;
  int count = 0;
};

namespace detail {

inline bool positionLess(const glm::vec4& a, const glm::vec4& b) {
  for (int i = 0; i < 4; ++i)
    if (a[i] != b[i]) return a[i] < b[i];
  return false;
}

template <int N>
ShadedVertex<N> intersect(const ShadedVertex<N>& a, const ShadedVertex<N>& b,
                          const ClipPlane& plane) {
  const bool swap = positionLess(b.position, a.position);
  const ShadedVertex<N>& p = swap ? b : a;
  const ShadedVertex<N>& q = swap ? a : b;
  const double dp = signedDistance(plane, p.position), dq = signedDistance(plane, q.position);
  const double t = dp / (dp - dq);  // dp and dq have opposite signs: |t| <= 1, no division by 0
  ShadedVertex<N> r;
  for (int i = 0; i < 4; ++i)
    r.position[i] = float(double(p.position[i]) + t * (double(q.position[i]) - p.position[i]));
  for (int i = 0; i < N; ++i)
    r.varyings[i] = float(double(p.varyings[i]) + t * (double(q.varyings[i]) - p.varyings[i]));
  return r;
}

}  // namespace detail

// Which of the planes each vertex is outside of, one bit per plane.
template <size_t P>
unsigned outsideMask(const std::array<ClipPlane, P>& planes, const glm::vec4& position) {
  unsigned mask = 0;
  for (size_t i = 0; i < P; ++i)
    if (signedDistance(planes[i], position) < 0) mask |= 1u << i;
  return mask;
}

// Clips the triangle against the planes whose bits are set in `planeMask`. The polygon keeps the
// triangle's winding; it has 0 or 3..kMaxClipVertices vertices.
template <int N>
void clipTriangle(const std::array<const ShadedVertex<N>*, 3>& tri, const ClipPlanes& planes,
                  unsigned planeMask, ClipPolygon<N>& out) {
  ClipPolygon<N> scratch;
  ClipPolygon<N>* in = &scratch;
  ClipPolygon<N>* result = &out;
  for (int i = 0; i < 3; ++i) in->vertices[i] = *tri[i];
  in->count = 3;
  for (int p = 0; p < ClipPlanes::kClipPlaneCount; ++p) {
    if (!(planeMask & (1u << p))) continue;
    const ClipPlane& plane = planes.clip[p];
    result->count = 0;
    // A convex polygon gains at most one vertex per plane; only a polygon made non-convex by
    // rounding could gain more, and such a sliver is dropped rather than overflow the array.
    bool overflow = false;
    auto push = [&](const ShadedVertex<N>& v) {
      if (result->count == kMaxClipVertices) overflow = true;
      else result->vertices[result->count++] = v;
    };
    for (int i = 0; i < in->count; ++i) {
      const ShadedVertex<N>& cur = in->vertices[i];
      const ShadedVertex<N>& next = in->vertices[(i + 1) % in->count];
      const double dCur = signedDistance(plane, cur.position);
      const double dNext = signedDistance(plane, next.position);
      if (dCur >= 0) push(cur);
      // A vertex exactly on the plane is kept as it is; a crossing adds a vertex only between
      // one strictly inside and one strictly outside.
      if ((dCur > 0 && dNext < 0) || (dCur < 0 && dNext > 0))
        push(detail::intersect(cur, next, plane));
    }
    std::swap(in, result);
    if (overflow || in->count < 3) {
      out.count = 0;
      return;
    }
  }
  if (in != &out) out = *in;
}

}  // namespace rast
