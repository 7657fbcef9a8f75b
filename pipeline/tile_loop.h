// The back end: per tile, per binned triangle in submission order, coverage (raster), then per
// covered pixel early depth, interpolation, the pixel shader and the output merger.
#pragma once

#include <bit>
#include <span>
#include <type_traits>
#include <vector>

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "pipeline/bin.h"
#include "rasterizer/coverage_kernels.h"
#include "pipeline/interpolate.h"
#include "pipeline/merge.h"
#include "pipeline/shader.h"

namespace rast {

template <PixelShader PS, class Merge, int N = PS::kVaryings>
void processFragment(const SetupTriangle<N>& t, int px, int py, const PS& shader,
                     const MergeTarget& target, size_t pixel, PipelineStatistics& stats) {
  constexpr bool kDepthTest = Merge::kCompare != CompareOp::Always;
  // With colour writes off, a shader that cannot discard has no visible effect: skip it.
  constexpr bool kShade = Merge::kColorWrite || PS::kMayDiscard;
  const float dx = float(px - t.bounds.x0), dy = float(py - t.bounds.y0);
  const float z = interpolateDepth(t, dx, dy);

  auto depthTest = [&] {
    if (depthPasses<Merge::kCompare>(z, target.depth[pixel])) {
      ++stats.depthTestsPassed;
      return true;
    }
    ++stats.depthTestsFailed;
    return false;
  };
  if constexpr (kDepthTest && (Merge::kEarlyDepth || !kShade)) {
    if (!depthTest()) return;
  }
  PixelResult result;
  if constexpr (kShade) {
    Fragment<N> fragment;
    interpolateVaryings<N>(t, dx, dy, fragment.varyings);
    fragment.x = px;
    fragment.y = py;
    fragment.depth = z;
    fragment.frontFacing = t.frontFacing;
    fragment.primitiveId = t.primitiveId;
    result = shader(fragment);
    ++stats.pixelShaderInvocations;
    if constexpr (PS::kMayDiscard) {
      if (result.discard) {
        ++stats.fragmentsDiscarded;
        return;
      }
    }
    if constexpr (kDepthTest && !Merge::kEarlyDepth) {
      if (!depthTest()) return;
    }
  }
  if constexpr (Merge::kDepthWrite) target.depth[pixel] = z;
  if constexpr (Merge::kColorWrite) target.color[pixel] = packColor(result.color);
  if constexpr (Merge::kCountFragments) ++target.counts[pixel];
  ++stats.fragmentsWritten;
}

template <PixelShader PS, class Merge, int N = PS::kVaryings>
void rasterizeTile(int tileX, int tileY, std::span<const uint32_t> bin,
                   const std::vector<SetupTriangle<N>>& triangles, const PS& shader,
                   FixedPointFormat format, const CoverageKernel& kernel,
                   const MergeTarget& target, int framebufferWidth, PipelineStatistics& stats) {
  for (const uint32_t index : bin) {
    const SetupTriangle<N>& t = triangles[index];
    const TileCoverageResult coverage = coverTile(kernel, t.edges, t.bounds, tileX, tileY, format);
    switch (coverage.kind) {
      case TileCoverage::Outside:
        ++stats.tilesTriviallyRejected;
        continue;
      case TileCoverage::Inside:
        ++stats.tilesTriviallyAccepted;
        break;
      case TileCoverage::Partial:
        ++stats.tilesPartial;
        break;
    }
    CoverageMask mask = coverage.mask;
    stats.samplesCovered += uint64_t(std::popcount(mask));
    for (; mask; mask &= mask - 1) {
      const int bit = std::countr_zero(mask);
      const int px = tileX * kTileSize + bit % kTileSize;
      const int py = tileY * kTileSize + bit / kTileSize;
      processFragment<PS, Merge>(t, px, py, shader, target, size_t(py) * framebufferWidth + px,
                                 stats);
    }
  }
}

namespace detail {

template <class F>
void withCompareOp(CompareOp op, F&& f) {
  using enum CompareOp;
  switch (op) {
    case Never: return f(std::integral_constant<CompareOp, Never>{});
    case Less: return f(std::integral_constant<CompareOp, Less>{});
    case Equal: return f(std::integral_constant<CompareOp, Equal>{});
    case LessEqual: return f(std::integral_constant<CompareOp, LessEqual>{});
    case Greater: return f(std::integral_constant<CompareOp, Greater>{});
    case NotEqual: return f(std::integral_constant<CompareOp, NotEqual>{});
    case GreaterEqual: return f(std::integral_constant<CompareOp, GreaterEqual>{});
    case Always: return f(std::integral_constant<CompareOp, Always>{});
  }
}

template <class F>
void withFlag(bool flag, F&& f) {
  if (flag) f(std::true_type{});
  else f(std::false_type{});
}

}  // namespace detail

// Runs every tile, specialised once per draw on the merge state. Tiles run in parallel: each
// pixel belongs to one tile, and one task owns a tile, so no two tasks touch the same pixel, and
// within a tile triangles merge in submission order; statistics are sums, the same in any order.
template <PixelShader PS, int N = PS::kVaryings>
void runBackEnd(Framebuffer& fb, const PipelineState& state, const TileBins& bins,
                const std::vector<SetupTriangle<N>>& triangles, const PS& shader,
                const CoverageKernel& kernel, PipelineStatistics& stats) {
  const MergeTarget target{fb.colorPlane().data(), fb.depthPlane().data(),
                           fb.hasCounts() ? fb.countPlane().data() : nullptr};
  detail::withCompareOp(state.depth.compare, [&](auto op) {
    detail::withFlag(state.depth.write, [&](auto depthWrite) {
      detail::withFlag(state.colorWrite, [&](auto colorWrite) {
        detail::withFlag(state.depth.early, [&](auto early) {
          detail::withFlag(fb.hasCounts(), [&](auto count) {
            using Merge = MergeConfig<decltype(op)::value, decltype(depthWrite)::value,
                                      decltype(colorWrite)::value, decltype(early)::value,
                                      decltype(count)::value>;
            tbb::combinable<PipelineStatistics> perTask;
            tbb::parallel_for(0, bins.tileCount(), [&](int tile) {
              const int tx = tile % bins.tilesX(), ty = tile / bins.tilesX();
              rasterizeTile<PS, Merge>(tx, ty, bins.bin(tile), triangles, shader, state.format,
                                       kernel, target, fb.width(), perTask.local());
            });
            perTask.combine_each([&](const PipelineStatistics& s) { stats += s; });
          });
        });
      });
    });
  });
}

}  // namespace rast
