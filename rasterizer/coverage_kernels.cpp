// One kernel source compiled for every Highway target (foreach_target re-includes this file once
// per instruction set); the table at the bottom picks the versions this CPU can run.
#include "rasterizer/coverage_kernels.h"

#include <algorithm>
#include <cctype>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "rasterizer/coverage_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace rast {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Evaluates the listed edges at all 64 samples, Lanes(d) samples at a time. Sample k of the tile
// is pixel (k % 8, k / 8); E(k) = e0 + (k % 8) * dx + (k / 8) * dy. Every partial sum is the value
// of E at some sample of the tile, so it fits in int32 by the precondition of TileEdgeSteps.
CoverageMask CoverTileEdges(const TileEdgeSteps& edges) {
  const hn::ScalableTag<int32_t> d;
  const size_t lanes = hn::Lanes(d);
  const auto minusOne = hn::Set(d, -1);
  const auto seven = hn::Set(d, 7);
  CoverageMask mask = 0;
  for (size_t base = 0; base < 64; base += lanes) {
    const auto k = hn::Iota(d, int32_t(base));
    const auto x = hn::And(k, seven);
    const auto y = hn::ShiftRight<3>(k);
    auto inside = hn::FirstN(d, lanes);
    for (int i = 0; i < edges.count; ++i) {
      const auto e = hn::Add(hn::Add(hn::Set(d, edges.e0[i]), hn::Mul(x, hn::Set(d, edges.dx[i]))),
                             hn::Mul(y, hn::Set(d, edges.dy[i])));
      inside = hn::And(inside, hn::Gt(e, minusOne));  // E >= 0, the biased fill-rule test
    }
    uint8_t bits[8] = {};
    hn::StoreMaskBits(d, inside, bits);
    uint64_t chunk = 0;
    for (size_t b = 0; b < (lanes + 7) / 8; ++b) chunk |= uint64_t(bits[b]) << (8 * b);
    if (lanes < 64) chunk &= (uint64_t{1} << lanes) - 1;
    mask |= chunk << base;
  }
  return mask;
}

}  // namespace HWY_NAMESPACE
}  // namespace rast
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rast {

HWY_EXPORT(CoverTileEdges);

namespace {

// Highway's dispatch table holds one entry per target bit (null where not compiled) and the
// EMU128/scalar fallback last; index it directly so a user can choose any compiled target.
CoverageKernelFn kernelForTarget(int64_t target) {
  const int64_t shifted = HWY_CHOSEN_TARGET_SHIFT(target);
  const size_t index = shifted ? size_t(hwy::Num0BitsBelowLS1Bit_Nonzero64(uint64_t(shifted)))
                               : size_t(HWY_MAX_DYNAMIC_TARGETS + 1);
  return HWY_DISPATCH_TABLE(CoverTileEdges)[index];
}

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = char(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

}  // namespace

std::vector<CoverageKernel> availableCoverageKernels() {
  std::vector<CoverageKernel> kernels{{"scalar", nullptr}};
  std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  // Highway lists the best target first (lowest bit); ours ends with the best.
  std::reverse(targets.begin(), targets.end());
  for (int64_t t : targets) {
    CoverageKernelFn fn = kernelForTarget(t);
    if (!fn) continue;
    // Highway's own one-lane fallback is also called SCALAR; ours (the int64 reference) keeps
    // the plain name.
    const std::string name = hwy::TargetName(t);
    kernels.push_back({name == "SCALAR" ? "HWY_SCALAR" : name, fn});
  }
  return kernels;
}

CoverageKernel bestCoverageKernel() {
  static const CoverageKernel best = availableCoverageKernels().back();  // the CPU does not change
  return best;
}

bool findCoverageKernel(std::string_view name, CoverageKernel& out) {
  const std::string wanted = lower(name);
  if (wanted == "auto") {
    out = bestCoverageKernel();
    return true;
  }
  for (const CoverageKernel& k : availableCoverageKernels())
    if (lower(k.name) == wanted) {
      out = k;
      return true;
    }
  return false;
}

CoverageMask coverTile(const CoverageKernel& kernel, const std::array<EdgeFunction, 3>& edges,
                       const PixelRect& bounds, int tileX, int tileY, FixedPointFormat format) {
  if (!kernel.simd) return coverageScalar(edges, bounds, tileX, tileY, format);

  // Per edge, from its exact int64 value at the tile's first sample: all 64 samples inside or
  // outside (no per-sample work), or the edge's values over the tile span at most
  // 7 * (|dx| + |dy|) around zero. When that span is below 2^31, every value over the tile is an
  // int32 (lo < 0 <= hi and hi - lo = 7(|dx| + |dy|)), and 32-bit lanes are exact. Longer edges
  // (beyond ~1.2M pixels in 24.4, ~4,600 in 16.8) take the int64 reference path.
  const int64_t sx0 = pixelCentreSubpixels(tileX * kTileSize, format);
  const int64_t sy0 = pixelCentreSubpixels(tileY * kTileSize, format);
  const int64_t step = format.subpixelsPerPixel();
  TileEdgeSteps steps;
  bool needsWide = false;
  for (const EdgeFunction& e : edges) {
    const int64_t e00 = e.at(sx0, sy0), dx = e.a * step, dy = e.b * step;
    const int64_t spanX = (kTileSize - 1) * dx, spanY = (kTileSize - 1) * dy;
    const int64_t lo = e00 + std::min<int64_t>(spanX, 0) + std::min<int64_t>(spanY, 0);
    const int64_t hi = e00 + std::max<int64_t>(spanX, 0) + std::max<int64_t>(spanY, 0);
    if (hi < 0) return 0;
    if (lo >= 0) continue;
    if (hi - lo >= (int64_t{1} << 31)) {
      needsWide = true;
      continue;
    }
    steps.e0[steps.count] = int32_t(e00);
    steps.dx[steps.count] = int32_t(dx);
    steps.dy[steps.count] = int32_t(dy);
    ++steps.count;
  }
  if (needsWide) return coverageScalar(edges, bounds, tileX, tileY, format);
  const CoverageMask inRect = rectMask(bounds, tileX, tileY);
  return steps.count == 0 ? inRect : kernel.simd(steps) & inRect;
}

}  // namespace rast
#endif  // HWY_ONCE
