#include "pipeline/clip_codes.h"

#include <algorithm>
#include <iterator>

namespace rast::detail {
namespace {

[[gnu::always_inline]] inline void testAxisPlanesBody(const std::vector<AxisPlane>& planes,
                                                      ClipCodeBlock& block) {
  // x - x is +0 for every finite x and NaN for an infinity or a NaN, so the sum of the four is
  // zero exactly when the position is finite: isfinite of each, in lanes.
  for (int i = 0; i < kClipCodeBlock; ++i) {
    const double s = (block.p[0][i] - block.p[0][i]) + (block.p[1][i] - block.p[1][i]) +
                     (block.p[2][i] - block.p[2][i]) + (block.p[3][i] - block.p[3][i]);
    block.finite[i] = s == 0.0;
  }
  std::fill(std::begin(block.outside), std::end(block.outside), 0);
  std::fill(std::begin(block.unsure), std::end(block.unsure), 0);
  for (size_t k = 0; k < planes.size(); ++k) {
    const AxisPlane& plane = planes[k];
    const double* x = block.p[plane.axis];
    const double* w = block.p[3];
    const double a = plane.plane[plane.axis], b = plane.plane.w;
    const uint64_t bits = plane.bits, unsureBit = uint64_t{1} << k;
    // isOutside's filter (clip.h) without its two zero terms: the sum is within
    // 2^-52 * (|t0| + |t1|) + 2^-1074 of the exact value, well inside the bound.
    for (int i = 0; i < kClipCodeBlock; ++i) {
      const double t0 = a * x[i], t1 = b * w[i];
      const double d = t0 + t1;
      const double bound = (std::abs(t0) + std::abs(t1)) * 0x1p-50 + 0x1p-1000;
      const uint64_t out = d < -bound, in = d > bound;  // both 0 when the bound does not decide
      block.outside[i] |= bits & (0 - out);
      block.unsure[i] |= unsureBit & ((out | in) - 1);
    }
  }
}

void testAxisPlanesBaseline(const std::vector<AxisPlane>& planes, ClipCodeBlock& block) {
  testAxisPlanesBody(planes, block);
}

[[gnu::target("avx2")]] void testAxisPlanesAvx2(const std::vector<AxisPlane>& planes,
                                               ClipCodeBlock& block) {
  testAxisPlanesBody(planes, block);
}

// Eight doubles a lane: W2 tiny-1's million vertices a frame spend most of their clip codes here.
[[gnu::target("avx512f,avx512dq,avx512vl,avx512bw")]] void testAxisPlanesAvx512(
    const std::vector<AxisPlane>& planes, ClipCodeBlock& block) {
  testAxisPlanesBody(planes, block);
}

}  // namespace

ClipCodeIsa bestClipCodeIsa() {
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw"))
    return ClipCodeIsa::Avx512;
  return __builtin_cpu_supports("avx2") ? ClipCodeIsa::Avx2 : ClipCodeIsa::Baseline;
}

void testAxisPlanes(const std::vector<AxisPlane>& planes, ClipCodeBlock& block, ClipCodeIsa isa) {
  switch (isa) {
    case ClipCodeIsa::Avx512: testAxisPlanesAvx512(planes, block); return;
    case ClipCodeIsa::Avx2: testAxisPlanesAvx2(planes, block); return;
    case ClipCodeIsa::Baseline: testAxisPlanesBaseline(planes, block); return;
  }
}

}  // namespace rast::detail
