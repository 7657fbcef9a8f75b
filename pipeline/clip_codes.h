// Clip codes: per transformed vertex, whether it is finite and which planes it lies outside of,
// computed once per vertex so that primitive assembly tests three codes instead of three
// positions against thirteen planes.
//
// Every plane of ClipPlanes bounds one axis: its x, y, z coefficients have at most one nonzero,
// beside the w coefficient (viewport.cpp). So its value at p is a two-term sum a*p[axis] + b*w,
// and the thirteen planes are eleven distinct ones (the depth planes are both reject and clip
// planes). The codes are computed over blocks of vertices, one plane at a time, in loops the
// compiler vectorises. A plane of any other shape (none today) takes the general path.
//
// Same bits as outsideMask (clip.h), by construction: for a two-term plane isOutside's
// four-term sum adds two exact zeros, so its value and error bound are the ones computed here,
// and the few vertices where that bound does not decide go to isOutside itself.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "pipeline/clip.h"
#include "pipeline/execution.h"
#include "pipeline/shader.h"

namespace rast {

struct VertexClipCodes {
  bool finite;
  unsigned reject;  // bit i: outside ClipPlanes::reject[i]
  unsigned clip;    // bit i: outside ClipPlanes::clip[i]
};

// A plane whose only nonzero x, y, z coefficient is plane[axis] (if any): plane[axis] * p[axis] +
// plane.w * p.w >= 0. And the reject and clip bits it stands for.
struct AxisPlane {
  int axis;
  uint32_t bits;  // reject bits in 0..15, clip bits in 16..31
  ClipPlane plane;
};

// The plane-by-plane codes of one vertex (outsideMask), the reference the block evaluation
// equals; planes of other shapes take it.
inline VertexClipCodes referenceClipCodes(const glm::dvec4& p, const ClipPlanes& planes) {
  const bool finite =
      std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
  return {finite, finite ? outsideMask(planes.reject, p) : 0u,
          finite ? outsideMask(planes.clip, p) : 0u};
}

// The distinct planes of `planes` in two-term form; false when one has another shape.
inline bool axisPlanes(const ClipPlanes& planes, std::vector<AxisPlane>& out) {
  // Each set's bits fit its 16, and a plane's index fits the 64-bit undecided mask.
  static_assert(std::tuple_size_v<decltype(planes.reject)> <= 16 &&
                ClipPlanes::kClipPlaneCount <= 16);
  out.clear();
  auto add = [&](const ClipPlane& p, uint32_t bit) {
    int axis = 0, nonzero = 0;
    for (int i = 0; i < 3; ++i)
      if (p[i] != 0) {
        axis = i;
        ++nonzero;
      }
    if (nonzero > 1) return false;
    for (AxisPlane& q : out)
      if (q.plane == p) {
        q.bits |= bit;
        return true;
      }
    out.push_back({axis, bit, p});
    return true;
  };
  for (size_t i = 0; i < planes.reject.size(); ++i)
    if (!add(planes.reject[i], 1u << i)) return false;
  for (size_t i = 0; i < planes.clip.size(); ++i)
    if (!add(planes.clip[i], 1u << (16 + i))) return false;
  return true;
}

namespace detail {

inline constexpr int kClipCodeBlock = 64;

// One block of positions, a column per coordinate.
struct ClipCodeBlock {
  alignas(64) double p[4][kClipCodeBlock];
  // Per vertex: the bits of the planes it is outside of (reject in 0..15, clip in 16..31), and
  // the planes (by index) whose error bound did not decide. 64-bit lanes, as wide as the
  // doubles they come from, so that the loops need no packing.
  alignas(64) uint64_t outside[kClipCodeBlock];
  alignas(64) uint64_t unsure[kClipCodeBlock];
  alignas(64) uint64_t finite[kClipCodeBlock];  // 1 where all four coordinates are finite
};

// The builds of testAxisPlanes, and the best one this CPU runs.
enum class ClipCodeIsa { Baseline, Avx2, Avx512 };
ClipCodeIsa bestClipCodeIsa();

// Fills `finite`, `outside` and `unsure` from `p` (clip_codes.cpp): loops over the block, one per
// plane, compiled for the x86-64 baseline, for AVX2 and for AVX-512 (`isa` picks; the CPU must
// have it). The same IEEE operations in each (no FMA: -ffp-contract=off), so the same bits.
void testAxisPlanes(const std::vector<AxisPlane>& planes, ClipCodeBlock& block, ClipCodeIsa isa);

template <int N>
void clipCodesBlock(const ShadedVertex<N>* vertices, int n, const std::vector<AxisPlane>& planes,
                    ClipCodeIsa isa, VertexClipCodes* out) {
  ClipCodeBlock block;
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) block.p[c][i] = double(vertices[i].position[c]);
  for (int c = 0; c < 4; ++c)
    for (int i = n; i < kClipCodeBlock; ++i) block.p[c][i] = 0;
  testAxisPlanes(planes, block, isa);
  for (int i = 0; i < n; ++i) {
    if (!block.finite[i]) {
      out[i] = {false, 0u, 0u};
      continue;
    }
    uint32_t bits = uint32_t(block.outside[i]);
    for (uint64_t m = block.unsure[i]; m; m &= m - 1) {
      const AxisPlane& plane = planes[size_t(std::countr_zero(m))];
      const glm::dvec4 v(block.p[0][i], block.p[1][i], block.p[2][i], block.p[3][i]);
      if (isOutside(plane.plane, v)) bits |= plane.bits;
    }
    out[i] = {true, bits & 0xFFFFu, bits >> 16};
  }
}

}  // namespace detail

template <int N>
ScratchVector<VertexClipCodes> computeClipCodes(const ScratchVector<ShadedVertex<N>>& vertices,
                                                const ClipPlanes& planes) {
  ScratchVector<VertexClipCodes> codes(vertices.size(),
                                       ScratchAllocator<VertexClipCodes>(vertices.get_allocator()));
  std::vector<AxisPlane> axis;
  const bool twoTerm = axisPlanes(planes, axis);
  const detail::ClipCodeIsa isa = detail::bestClipCodeIsa();
  forEachChunk(vertices.size(), 4096, [&](size_t, size_t begin, size_t end) {
    if (twoTerm) {
      for (size_t i = begin; i < end; i += detail::kClipCodeBlock)
        detail::clipCodesBlock(&vertices[i], int(std::min<size_t>(detail::kClipCodeBlock, end - i)),
                               axis, isa, &codes[i]);
      return;
    }
    for (size_t i = begin; i < end; ++i)
      codes[i] = referenceClipCodes(glm::dvec4(vertices[i].position), planes);
  });
  return codes;
}

}  // namespace rast
