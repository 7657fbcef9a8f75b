// The back end: per tile, per binned triangle in submission order, coverage (raster), the early
// depth test of the covered samples, then per passing pixel interpolation, the pixel shader and
// the output merger.
#pragma once

#include <algorithm>
#include <bit>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "pipeline/bin.h"
#include "pipeline/interpolate.h"
#include "pipeline/merge.h"
#include "pipeline/shader.h"
#include "rasterizer/coverage_kernels.h"

namespace rast {

// What one task needs to run a tile; the same for every tile of a draw.
template <PixelShader PS, int N = PS::kVaryings>
struct TileContext {
  const ScratchVector<SetupTriangle<N>>& triangles;
  const PS& shader;
  FixedPointFormat format;
  CoverageKernel kernel;
  MergeTarget target;
  int framebufferWidth;
  int framebufferHeight;
  RasterMode rasterMode = RasterMode::FixedPoint;
};

// Bounds of the depth values stored in a tile, so a triangle whose depth range lies entirely on
// the failing side of them fails for the whole tile without per-sample tests (and entirely on
// the passing side, passes without them). Exact, not approximate: the plane is evaluated in float
// as (at0 + ddx*dx) + ddy*dy, and every step of that is monotonic in dx and in dy, so the float
// value at any sample of the tile lies between the float values at the tile's corner samples.
// A NaN stored depth (only a NaN clear value makes one) fails every ordered compare, so it
// cannot spoil "all fail" but forbids "all pass".
struct TileDepthBounds {
  float min = 0, max = 0;
  bool hasNaN = false;
  bool valid = false;
};

template <CompareOp Op>
constexpr bool kOrderedCompare = Op == CompareOp::Less || Op == CompareOp::LessEqual ||
                                 Op == CompareOp::Greater || Op == CompareOp::GreaterEqual;

template <CompareOp Op>
constexpr bool allFail(float triMin, float triMax, const TileDepthBounds& b) {
  if constexpr (Op == CompareOp::Less) return triMin >= b.max;
  else if constexpr (Op == CompareOp::LessEqual) return triMin > b.max;
  else if constexpr (Op == CompareOp::Greater) return triMax <= b.min;
  else return triMax < b.min;  // GreaterEqual
}

template <CompareOp Op>
constexpr bool allPass(float triMin, float triMax, const TileDepthBounds& b) {
  if (b.hasNaN) return false;
  if constexpr (Op == CompareOp::Less) return triMax < b.min;
  else if constexpr (Op == CompareOp::LessEqual) return triMax <= b.min;
  else if constexpr (Op == CompareOp::Greater) return triMin > b.max;
  else return triMin >= b.max;  // GreaterEqual
}

// A fragment's depth as the depth buffer's format stores it: the value every compare and write
// uses. Quantising is monotonic, so the tile depth bounds above stay exact.
template <class Merge, int N>
float fragmentDepth(const SetupTriangle<N>& t, float dx, float dy) {
  return quantizeDepth<Merge::kDepthFormat>(interpolateDepth(t, dx, dy));
}

// The depth test of every sample in `mask`; returns those that pass.
template <class Merge, int N>
CoverageMask depthTestMask(const SetupTriangle<N>& t, CoverageMask mask, int tileX, int tileY,
                           const MergeTarget& target, int width) {
  CoverageMask pass = 0;
  for (CoverageMask m = mask; m; m &= m - 1) {
    const int bit = std::countr_zero(m);
    const int px = tileX * kTileSize + bit % kTileSize, py = tileY * kTileSize + bit / kTileSize;
    const float z = fragmentDepth<Merge>(t, float(px - t.bounds.x0), float(py - t.bounds.y0));
    if (depthPasses<Merge::kCompare>(z, target.depth[size_t(py) * width + px]))
      pass |= CoverageMask{1} << bit;
  }
  return pass;
}

// Interpolates, shades and merges one pixel whose early tests (if any) passed.
template <PixelShader PS, class Merge, int N = PS::kVaryings>
void shadeAndMerge(const SetupTriangle<N>& t, int px, int py, const PS& shader,
                   const MergeTarget& target, size_t pixel, PipelineStatistics& stats) {
  constexpr bool kDepthTest = Merge::kCompare != CompareOp::Always;
  // With colour writes off, a shader that cannot discard has no visible effect: skip it.
  constexpr bool kShade = Merge::kColorWrite || PS::kMayDiscard;
  constexpr bool kLateDepth = kDepthTest && !Merge::kEarlyDepth && kShade;
  const float dx = float(px - t.bounds.x0), dy = float(py - t.bounds.y0);
  const float z = fragmentDepth<Merge>(t, dx, dy);
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
  }
  if constexpr (kLateDepth) {
    if (!depthPasses<Merge::kCompare>(z, target.depth[pixel])) {
      ++stats.depthTestsFailed;
      return;
    }
    ++stats.depthTestsPassed;
  }
  if constexpr (Merge::kDepthWrite) target.depth[pixel] = z;
  if constexpr (Merge::kColorWrite) target.color[pixel] = packColor(result.color);
  if (target.counts) ++target.counts[pixel];
  ++stats.fragmentsWritten;
}

template <PixelShader PS, class Merge, int N = PS::kVaryings>
void rasterizeTile(int tileX, int tileY, std::span<const uint32_t> bin,
                   const TileContext<PS, N>& ctx, PipelineStatistics& stats) {
  constexpr CompareOp kOp = Merge::kCompare;
  constexpr bool kShade = Merge::kColorWrite || PS::kMayDiscard;
  // Depth tested before shading: always when no shader runs, else when early depth is on.
  constexpr bool kEarlyTest = kOp != CompareOp::Always && (Merge::kEarlyDepth || !kShade);
  constexpr bool kUseBounds = kEarlyTest && kOrderedCompare<kOp>;
  const int width = ctx.framebufferWidth;
  const int x0 = tileX * kTileSize, y0 = tileY * kTileSize;
  const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, ctx.framebufferHeight);
  TileDepthBounds stored;

  for (const uint32_t index : bin) {
    const SetupTriangle<N>& t = ctx.triangles[index];
    const TileCoverageResult coverage =
        ctx.rasterMode == RasterMode::Float
            ? coverTileFloat(t.floatEdges, t.bounds, tileX, tileY)
            : coverTile(ctx.kernel, t.edges, t.bounds, tileX, tileY, ctx.format);
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
    if (!mask) continue;
    const uint64_t covered = uint64_t(std::popcount(mask));
    stats.samplesCovered += covered;

    if constexpr (kEarlyTest) {
      CoverageMask pass;
      bool decided = false;
      if constexpr (kUseBounds) {
        if (!stored.valid) {
          stored = {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                    false, true};
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
              const float d = ctx.target.depth[size_t(y) * width + x];
              stored.hasNaN |= d != d;
              stored.min = d < stored.min ? d : stored.min;
              stored.max = d > stored.max ? d : stored.max;
            }
        }
        const float corners[4] = {
            fragmentDepth<Merge>(t, float(x0 - t.bounds.x0), float(y0 - t.bounds.y0)),
            fragmentDepth<Merge>(t, float(x1 - 1 - t.bounds.x0), float(y0 - t.bounds.y0)),
            fragmentDepth<Merge>(t, float(x0 - t.bounds.x0), float(y1 - 1 - t.bounds.y0)),
            fragmentDepth<Merge>(t, float(x1 - 1 - t.bounds.x0), float(y1 - 1 - t.bounds.y0))};
        const float triMin = std::min({corners[0], corners[1], corners[2], corners[3]});
        const float triMax = std::max({corners[0], corners[1], corners[2], corners[3]});
        if (allFail<kOp>(triMin, triMax, stored)) {
          stats.depthTestsFailed += covered;
          continue;
        }
        if (allPass<kOp>(triMin, triMax, stored)) {
          pass = mask;
          decided = true;
        }
      }
      if (!decided) pass = depthTestMask<Merge>(t, mask, tileX, tileY, ctx.target, width);
      const uint64_t passed = uint64_t(std::popcount(pass));
      stats.depthTestsPassed += passed;
      stats.depthTestsFailed += covered - passed;
      mask = pass;
      if (!mask) continue;
    }
    for (CoverageMask m = mask; m; m &= m - 1) {
      const int bit = std::countr_zero(m);
      const int px = x0 + bit % kTileSize, py = y0 + bit / kTileSize;
      shadeAndMerge<PS, Merge>(t, px, py, ctx.shader, ctx.target, size_t(py) * width + px, stats);
    }
    if constexpr (kUseBounds && Merge::kDepthWrite) stored.valid = false;
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
void withDepthFormat(DepthFormat format, F&& f) {
  using enum DepthFormat;
  switch (format) {
    case Float32: return f(std::integral_constant<DepthFormat, Float32>{});
    case Unorm24: return f(std::integral_constant<DepthFormat, Unorm24>{});
    case Unorm16: return f(std::integral_constant<DepthFormat, Unorm16>{});
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
                const ScratchVector<SetupTriangle<N>>& triangles, const PS& shader,
                const CoverageKernel& kernel, PipelineStatistics& stats) {
  const TileContext<PS, N> ctx{triangles,
                               shader,
                               state.format,
                               kernel,
                               {fb.colorPlane().data(), fb.depthPlane().data(),
                                fb.hasCounts() ? fb.countPlane().data() : nullptr},
                               fb.width(),
                               fb.height(),
                               state.rasterMode};
  detail::withCompareOp(state.depth.compare, [&](auto op) {
    detail::withFlag(state.depth.write, [&](auto depthWrite) {
      detail::withFlag(state.colorWrite, [&](auto colorWrite) {
        detail::withFlag(state.depth.early, [&](auto early) {
          detail::withDepthFormat(state.depth.format, [&](auto depthFormat) {
            using Merge = MergeConfig<decltype(op)::value, decltype(depthWrite)::value,
                                      decltype(colorWrite)::value, decltype(early)::value,
                                      decltype(depthFormat)::value>;
            tbb::combinable<PipelineStatistics> perTask;
            tbb::parallel_for(tbb::blocked_range<int>(0, bins.tileCount(), 8),
                              [&](const tbb::blocked_range<int>& tiles) {
              PipelineStatistics& local = perTask.local();
              for (int tile = tiles.begin(); tile != tiles.end(); ++tile)
                rasterizeTile<PS, Merge>(tile % bins.tilesX(), tile / bins.tilesX(),
                                         bins.bin(tile), ctx, local);
            });
            perTask.combine_each([&](const PipelineStatistics& s) { stats += s; });
          });
        });
      });
    });
  });
}

}  // namespace rast
