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

// Evaluates three edges at all 64 samples, Lanes(d) samples at a time. Sample k of the tile is
// pixel (k % 8, k / 8); E(k) = e0 + (k % 8) * dx + (k / 8) * dy. Every partial sum is the value
// of E at some sample of the tile, so it fits in int32 by the precondition of TileEdgeSteps. A
// sample is inside when no edge value is negative: one sign test of e0 | e1 | e2.
CoverageMask CoverTileEdges(const TileEdgeSteps& edges) {
  const hn::ScalableTag<int32_t> d;
  constexpr size_t kLanes = hn::MaxLanes(d);
  const auto k = hn::Iota(d, 0);
  const auto x = hn::And(k, hn::Set(d, 7));
  const auto minusOne = hn::Set(d, -1);
  auto start = [&](int i, auto xs, auto ys) {
    return hn::Add(hn::Add(hn::Set(d, edges.e0[i]), hn::Mul(xs, hn::Set(d, edges.dx[i]))),
                   hn::Mul(ys, hn::Set(d, edges.dy[i])));
  };
  auto insideBits = [&](auto e0, auto e1, auto e2) {
    uint8_t bits[8] = {};
    hn::StoreMaskBits(d, hn::Gt(hn::Or(hn::Or(e0, e1), e2), minusOne), bits);
    uint64_t b = 0;
    for (size_t i = 0; i < (kLanes + 7) / 8; ++i) b |= uint64_t(bits[i]) << (8 * i);
    return kLanes >= 64 ? b : b & ((uint64_t{1} << kLanes) - 1);
  };
  CoverageMask mask = 0;
  if constexpr (kLanes >= 8) {
    // Whole rows per vector: start once, then step down kLanes / 8 rows with one add per edge.
    const auto y = hn::ShiftRight<3>(k);
    auto e0 = start(0, x, y), e1 = start(1, x, y), e2 = start(2, x, y);
    constexpr int32_t kRows = int32_t(kLanes / 8);
    const auto s0 = hn::Set(d, kRows * edges.dy[0]), s1 = hn::Set(d, kRows * edges.dy[1]),
               s2 = hn::Set(d, kRows * edges.dy[2]);
    for (size_t base = 0; base < 64; base += kLanes) {
      mask |= insideBits(e0, e1, e2) << base;
      // The last step would leave the tile; skip it so no value outside the tile is formed.
      if (base + kLanes < 64) {
        e0 = hn::Add(e0, s0);
        e1 = hn::Add(e1, s1);
        e2 = hn::Add(e2, s2);
      }
    }
  } else {
    for (size_t base = 0; base < 64; base += kLanes) {
      const auto kk = hn::Iota(d, int32_t(base));
      const auto xs = hn::And(kk, hn::Set(d, 7)), ys = hn::ShiftRight<3>(kk);
      mask |= insideBits(start(0, xs, ys), start(1, xs, ys), start(2, xs, ys)) << base;
    }
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

CoverageKernelFn kernelForTarget(int64_t target) {
  return HWY_DISPATCH_TABLE(CoverTileEdges)[highwayTableIndex(target)];
}

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = char(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

}  // namespace

// Highway's dispatch table holds one entry per target bit (null where not compiled) and the
// EMU128/scalar fallback last; index it directly so a user can choose any compiled target.
size_t highwayTableIndex(int64_t target) {
  const int64_t shifted = HWY_CHOSEN_TARGET_SHIFT(target);
  return shifted ? size_t(hwy::Num0BitsBelowLS1Bit_Nonzero64(uint64_t(shifted)))
                 : size_t(HWY_MAX_DYNAMIC_TARGETS + 1);
}

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
    kernels.push_back({name == "SCALAR" ? "HWY_SCALAR" : name, fn, t});
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

TileCoverageResult coverTile(const CoverageKernel& kernel,
                             const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                             int tileX, int tileY, FixedPointFormat format,
                             int32_t offsetX, int32_t offsetY) {
  // Per edge, from its exact int64 value at the tile's first sample: all 64 samples inside or
  // all outside (no per-sample work), or the edge's values over the tile span
  // 7 * (|dx| + |dy|) across zero. When that span is below 2^31, every value over the tile is an
  // int32 (lo < 0 <= hi and hi - lo = 7(|dx| + |dy|)), and 32-bit lanes are exact. Longer edges
  // (beyond ~1.2M pixels in 24.4, ~4,600 in 16.8) take the int64 reference path.
  const int64_t sx0 = pixelCentreSubpixels(tileX * kTileSize, format) + offsetX;
  const int64_t sy0 = pixelCentreSubpixels(tileY * kTileSize, format) + offsetY;
  const int64_t step = format.subpixelsPerPixel();
  // Edges that always pass (inside over the whole tile) are listed as the constant 0.
  TileEdgeSteps steps{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0};
  bool needsWide = false;
  for (const EdgeFunction& e : edges) {
    const int64_t e00 = e.at(sx0, sy0), dx = int64_t{e.a} * step, dy = int64_t{e.b} * step;
    const EdgeExtent extent = edgeExtent(e, kTileSize, kTileSize, format, 0);
    const int64_t lo = e00 + extent.lowest, hi = e00 + extent.highest;
    if (hi < 0) return {0, TileCoverage::Outside};
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
  const CoverageMask inRect = rectMask(bounds, tileX, tileY);
  if (steps.count == 0 && !needsWide)
    return {inRect, inRect == kFullMask ? TileCoverage::Inside : TileCoverage::Partial};
  if (needsWide || !kernel.simd)
    return {coverageScalar(edges, bounds, tileX, tileY, format, offsetX, offsetY),
            TileCoverage::Partial};
  return {kernel.simd(steps) & inRect, TileCoverage::Partial};
}

}  // namespace rast
#endif  // HWY_ONCE
