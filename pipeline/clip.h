// Clipping in homogeneous space (Sutherland-Hodgman), against the planes of ClipPlanes::clip.
//
// Clipped vertices keep their position in double: the guard band reaches 2^22 pixels in 24.4,
// where a float position would be 0.25 px off, eight times the snapping step.
//
// Watertightness across clipped edges: the crossing point of an edge is the convex combination
//   (|d_q| p + |d_p| q) / (|d_p| + |d_q|)
// with d the signed distances to the plane. It is symmetric in p and q (IEEE addition and
// multiplication commute), so two triangles sharing an edge get bit-identical new vertices
// whichever way they walk it; and with both weights positive nothing cancels, so it stays
// accurate when the endpoints' distances differ by many orders of magnitude (w from 1e-20 to 1e25).
#pragma once

#include <array>
#include <cmath>
#include <cstring>

#include "pipeline/shader.h"
#include "pipeline/statistics.h"
#include "pipeline/viewport.h"

namespace rast {

inline constexpr int kMaxClipVertices = 3 + ClipPlanes::kClipPlaneCount;

// A vertex made or kept by the clipper.
template <int N>
struct ClippedVertex {
  glm::dvec4 position;
  Varyings<N> varyings{};
};

template <int N>
struct ClipPolygon {
  std::array<ClippedVertex<N>, kMaxClipVertices> vertices;
  int count = 0;
};

namespace detail {

// Every clip plane bounds one window axis: coefficients (x, y, z) have at most one nonzero. Along
// that axis the crossing point is known exactly from its w (it lies on the plane), while
// interpolating it would take the difference of the endpoints' huge coordinates, so it is set.
template <int N>
ClippedVertex<N> intersect(const ClippedVertex<N>& p, const DoubleDouble& dp,
                           const ClippedVertex<N>& q, const DoubleDouble& dq,
                           const ClipPlane& plane) {
  // The weights' difference carries the answer when p and q are huge and far apart, so they and
  // the numerators stay in double-double; addition stays commutative, keeping the symmetry.
  const DoubleDouble wp = dq.abs(), wq = dp.abs(), total = wp + wq;
  ClippedVertex<N> r;
  for (int i = 0; i < 4; ++i) r.position[i] = divide(wp * p.position[i] + wq * q.position[i], total);
  int axis = 3;
  for (int i = 0; i < 3; ++i)
    if (plane[i] != 0) axis = i;
  if (axis == 3) r.position.w = 0;  // the plane w >= 0
  else r.position[axis] = -plane.w * r.position.w / plane[axis];
  for (int i = 0; i < N; ++i)
    r.varyings[i] = float(divide(wp * double(p.varyings[i]) + wq * double(q.varyings[i]), total));
  return r;
}

}  // namespace detail

// Whether dot(plane, p) < 0, exactly. A floating-point filter first: the plain double sum of
// four products is within gamma_4 * sum|terms| (gamma_4 ~ 4 * 2^-53) of the exact value, plus at
// most 2^-1072 from underflowed products, so beyond 2^-50 * sum|terms| + 2^-1000 its sign is the
// exact sign. Only vertices that close to a plane pay for the double-double sum. (An overflowed
// product makes the bound infinite, which also falls through to the exact sum.)
inline bool isOutside(const ClipPlane& plane, const glm::dvec4& p) {
  const double t0 = plane[0] * p[0], t1 = plane[1] * p[1], t2 = plane[2] * p[2],
               t3 = plane[3] * p[3];
  const double d = ((t0 + t1) + t2) + t3;
  const double bound =
      (((std::abs(t0) + std::abs(t1)) + std::abs(t2)) + std::abs(t3)) * 0x1p-50 + 0x1p-1000;
  if (d > bound) return false;
  if (d < -bound) return true;
  return signedDistance(plane, p) < 0;
}

// Which of the planes each vertex is outside of, one bit per plane.
template <size_t P>
unsigned outsideMask(const std::array<ClipPlane, P>& planes, const glm::dvec4& position) {
  unsigned mask = 0;
  for (size_t i = 0; i < P; ++i)
    if (isOutside(planes[i], position)) mask |= 1u << i;
  return mask;
}

// Clips the triangle against the planes whose bits are set in `planeMask`. The polygon keeps the
// triangle's winding; it has 0 or 3..kMaxClipVertices vertices. `stats`, when given, counts the
// polygons into and out of each plane.
template <int N>
void clipTriangle(const std::array<const ShadedVertex<N>*, 3>& tri, const ClipPlanes& planes,
                  unsigned planeMask, ClipPolygon<N>& out, PipelineStatistics* stats = nullptr) {
  static_assert(kClipPlaneCounters.size() == ClipPlanes::kClipPlaneCount);
  ClipPolygon<N> scratch;
  ClipPolygon<N>* in = &scratch;
  ClipPolygon<N>* result = &out;
  for (int i = 0; i < 3; ++i) in->vertices[i] = {glm::dvec4(tri[i]->position), tri[i]->varyings};
  in->count = 3;
  for (int p = 0; p < ClipPlanes::kClipPlaneCount; ++p) {
    if (!(planeMask & (1u << p))) continue;
    const ClipPlane& plane = planes.clip[p];
    if (stats) ++(stats->*kClipPlaneCounters[p].first);
    result->count = 0;
    // A convex polygon gains at most one vertex per plane; only a polygon made non-convex by
    // rounding could gain more, and such a sliver is dropped rather than overflow the array.
    bool overflow = false;
    auto push = [&](const ClippedVertex<N>& v) {
      if (result->count == kMaxClipVertices) overflow = true;
      else result->vertices[result->count++] = v;
    };
    for (int i = 0; i < in->count; ++i) {
      const ClippedVertex<N>& cur = in->vertices[i];
      const ClippedVertex<N>& next = in->vertices[(i + 1) % in->count];
      const DoubleDouble dCur = signedDistanceExact(plane, cur.position);
      const DoubleDouble dNext = signedDistanceExact(plane, next.position);
      if (dCur.hi >= 0) push(cur);
      // A vertex exactly on the plane is kept as it is; a crossing adds a vertex only between
      // one strictly inside and one strictly outside.
      if ((dCur.hi > 0 && dNext.hi < 0) || (dCur.hi < 0 && dNext.hi > 0))
        push(detail::intersect(cur, dCur, next, dNext, plane));
    }
    std::swap(in, result);
    if (overflow || in->count < 3) {
      out.count = 0;
      return;
    }
    if (stats) ++(stats->*kClipPlaneCounters[p].second);
  }
  if (in != &out) out = *in;
}

}  // namespace rast
