// Setup of unclipped triangles several at a time, for fixed-point rasterization.
//
// Setup one triangle at a time is bound by its instruction count (W2 tiny-1: about 45 ns a
// triangle, and neither overlapping several triangles' steps nor an AVX2 build of the scalar code
// made it faster). A batch holds the corners of up to kSetupLanes triangles a column per
// coordinate, and runs the floating-point steps (window position, snapping, the planes) as loops
// over the triangles, which the compiler vectorises: in a build for the x86-64 baseline and one
// for AVX2 and one for AVX-512, chosen at run time. The integer steps (edge functions, fill
// rule, bounds) run over the lanes as well, in 32- and 64-bit integers.
//
// Same bits and counters as setupTriangle (setup.h): each lane does setupTriangle's IEEE
// operations in the same order (no FMA: -ffp-contract=off), and a non-finite corner makes its
// triangle take setupTriangle's early exit. tests/setup_batch_test.cpp compares them.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "pipeline/execution.h"
#include "pipeline/setup.h"

namespace rast {
namespace detail {

// 32: against 16, setup 0.94-0.95x on W2 and 1.01x on W1 and W4.
inline constexpr int kSetupLanes = 32;

// The builds of the batch's loops: the same source and the same IEEE operations in each.
enum class SetupIsa { Baseline, Avx2, Avx512 };
// The best one this CPU runs.
SetupIsa bestSetupIsa();
const char* setupIsaName(SetupIsa isa);

// Window position and snapping of a batch. In: `p`, the corners' positions (double of the
// vertex's float). Out: window depth and 1/w, the snapped corners and, per lane, whether every
// value is finite (a lane that is not has zero snapped corners).
struct SetupCorners {
  alignas(64) double p[3][4][kSetupLanes];  // corner, coordinate (x, y, z, w), lane
  alignas(64) double z[3][kSetupLanes];
  alignas(64) double invW[3][kSetupLanes];
  alignas(64) int32_t x[3][kSetupLanes];  // subpixels
  alignas(64) int32_t y[3][kSetupLanes];
  alignas(64) int64_t finite[kSetupLanes];  // 0 or 1
};

struct SetupCornersConstants {
  double scale[3], offset[3];
  double subpixelsPerPixel, guardBand;  // guardBand: FixedPointFormat::guardBandSubpixels
};

void windowAndSnap(const SetupCornersConstants& k, int lanes, SetupCorners& c, SetupIsa isa);

// setupCoverage (rasterizer/triangle_setup.cpp) of each lane's snapped corners, in integers.
struct SetupCoverageLanes {
  alignas(64) int32_t outcome[kSetupLanes];    // SetupOutcome
  alignas(64) int32_t clockwise[kSetupLanes];  // 0 or 1
  alignas(64) int32_t a[3][kSetupLanes];       // EdgeFunction of edge e
  alignas(64) int32_t b[3][kSetupLanes];
  alignas(64) int64_t c[3][kSetupLanes];
  alignas(64) int32_t x0[kSetupLanes];  // PixelRect
  alignas(64) int32_t y0[kSetupLanes];
  alignas(64) int32_t x1[kSetupLanes];
  alignas(64) int32_t y1[kSetupLanes];
};
struct SetupCoverageConstants {
  PixelRect clip;
  int fractionBits;
  FillRule rule;
  int32_t sampleReach;
};
void coverageLanes(const SetupCoverageConstants& k, const SetupCorners& c, int lanes,
                   SetupCoverageLanes& out, SetupIsa isa);

// The planes through each lane's snapped corners, for one attribute: `value[corner][lane]`.
struct SetupPlaneInputs {
  alignas(64) double x[3][kSetupLanes];  // corners in pixels
  alignas(64) double y[3][kSetupLanes];
  alignas(64) double inverseDoubleArea[kSetupLanes];
};
struct SetupPlanes {
  alignas(64) float at0[kSetupLanes];
  alignas(64) float ddx[kSetupLanes];
  alignas(64) float ddy[kSetupLanes];
};

// x, y from the snapped corners, and 1 / twice the area (inverseDoubleArea).
void planeGeometry(const SetupCorners& c, double pixelsPerSubpixel, int lanes,
                   SetupPlaneInputs& out, SetupIsa isa);
// Anchored at the origin of each lane's bounds (coverageLanes).
void planesThrough(const SetupPlaneInputs& in, const SetupCoverageLanes& bounds,
                   const double (&value)[3][kSetupLanes], int lanes, SetupPlanes& out, SetupIsa isa);

}  // namespace detail

template <int N>
class SetupBatch {
 public:
  static constexpr int kCapacity = detail::kSetupLanes;

  // `isa`: the build of the vector steps to run (the CPU must have it); every one gives the same
  // bits.
  SetupBatch(const SetupContext& ctx, detail::SetupIsa isa) : ctx_(ctx), isa_(isa) {
    for (int a = 0; a < 3; ++a) {
      constants_.scale[a] = ctx.mapping.scale[a];
      constants_.offset[a] = ctx.mapping.offset[a];
    }
    constants_.subpixelsPerPixel = double(ctx.format.subpixelsPerPixel());
    constants_.guardBand = double(ctx.format.guardBandSubpixels());
    coverageConstants_ = {ctx.clipRect, ctx.format.fractionBits, ctx.fillRule, ctx.sampleReach};
  }

  bool full() const { return count_ == kCapacity; }

  void add(const std::array<const ShadedVertex<N>*, 3>& v, uint32_t primitiveId) {
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 4; ++c) corners_.p[i][c][count_] = double(v[i]->position[c]);
    // The varyings are read now, with the positions' cache lines: at the flush, up to 31
    // triangles later, they could be gone.
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < N; ++k) varyingValues_[k][i][count_] = double(v[i]->varyings[k]);
    primitiveIds_[count_] = primitiveId;
    ++count_;
  }

  // Sets up the batch's triangles, appends those drawn to `out` in the order they were added,
  // counts them as setupTriangle does, and empties the batch.
  void flush(ScratchVector<SetupTriangle<N>>& out, PipelineStatistics& stats) {
    const int n = count_;
    if (n == 0) return;
    count_ = 0;
    // The triangles' slots in `out` are rarely in cache (W2 tiny-1 writes 180 MB of them a
    // frame), and the first store to each waits on its line: the next batch's slots are fetched
    // for writing now, to arrive while this batch computes (W1 and W4 setup 0.9x; W2 1.01x).
    const size_t ahead = std::min(out.capacity() - out.size(), size_t(2 * kCapacity));
    const auto* slots = reinterpret_cast<const char*>(out.data() + out.size());
    for (size_t b = kCapacity * sizeof(SetupTriangle<N>); b < ahead * sizeof(SetupTriangle<N>);
         b += 64)
      __builtin_prefetch(slots + b, 1);
    detail::windowAndSnap(constants_, n, corners_, isa_);

    detail::coverageLanes(coverageConstants_, corners_, n, coverage_, isa_);

    // Each lane's verdict in a loop that vectorises (judgeCoverage has no branch); a lane whose
    // corners are not all finite gets kSetupVerdicts.
    alignas(64) int32_t verdict[kCapacity];
    for (int l = 0; l < n; ++l)
      verdict[l] = corners_.finite[l] ? int32_t(judgeCoverage(SetupOutcome(coverage_.outcome[l]),
                                                              coverage_.clockwise[l] != 0, ctx_))
                                      : kSetupVerdicts;
    for (int v = 1; v <= kSetupVerdicts; ++v) {
      int32_t count = 0;
      for (int l = 0; l < n; ++l) count += verdict[l] == v;
      if (v == kSetupVerdicts)
        stats.clipDegenerate += uint64_t(count);
      else
        countDropped(SetupVerdict(v), uint64_t(count), stats);
    }
    std::array<uint8_t, kCapacity> drawnLanes;
    int drawnCount = 0;
    for (int l = 0; l < n; ++l) {
      drawnLanes[drawnCount] = uint8_t(l);
      drawnCount += verdict[l] == int32_t(SetupVerdict::Drawn);
    }

    // Planes for every lane (those not drawn give values nobody reads).
    const double pixelsPerSubpixel = subpixelsToPixels(1, ctx_.format);
    detail::planeGeometry(corners_, pixelsPerSubpixel, n, planeInputs_, isa_);
    detail::planesThrough(planeInputs_, coverage_, corners_.z, n, depth_, isa_);
    if constexpr (N > 0) {
      detail::planesThrough(planeInputs_, coverage_, corners_.invW, n, invW_, isa_);
      for (int k = 0; k < N; ++k) {
        for (int i = 0; i < 3; ++i)
          for (int l = 0; l < n; ++l)
            overW_[i][l] = varyingValues_[k][i][l] * corners_.invW[i][l];
        detail::planesThrough(planeInputs_, coverage_, overW_, n, varyings_[k], isa_);
      }
    }

    for (int d = 0; d < drawnCount; ++d) {
      const int l = drawnLanes[d];
      // The record is assembled in a local and stored whole: built in place, emplace_back zeroed
      // it first (five stores more than the ten its fields take), and setup waited on the store
      // buffer (W2 tiny-1: a third of flush's samples at the record's first store).
      SetupTriangle<N> t;
      for (int e = 0; e < 3; ++e)
        t.edges[e] = {coverage_.a[e][l], coverage_.b[e][l], coverage_.c[e][l]};
      t.bounds = {coverage_.x0[l], coverage_.y0[l], coverage_.x1[l], coverage_.y1[l]};
      t.setPrimitive(primitiveIds_[l], facesFront(coverage_.clockwise[l] != 0, ctx_));
      t.depth = plane(depth_, l);
      if constexpr (N > 0) {
        t.invW = plane(invW_, l);
        for (int k = 0; k < N; ++k) t.varyingsOverW[k] = plane(varyings_[k], l);
      }
      out.push_back(t);
    }
    stats.setupTriangles += uint64_t(drawnCount);
  }

 private:
  static PlaneEquation plane(const detail::SetupPlanes& p, int lane) {
    return {p.at0[lane], p.ddx[lane], p.ddy[lane]};
  }

  SetupContext ctx_;
  detail::SetupIsa isa_;
  detail::SetupCornersConstants constants_;
  detail::SetupCoverageConstants coverageConstants_;
  detail::SetupCoverageLanes coverage_;
  int count_ = 0;
  detail::SetupCorners corners_;
  detail::SetupPlaneInputs planeInputs_;
  detail::SetupPlanes depth_;
  [[no_unique_address]] std::conditional_t<(N > 0), detail::SetupPlanes, NoPlane> invW_;
  std::array<detail::SetupPlanes, N> varyings_;
  alignas(64) double overW_[3][detail::kSetupLanes];
  // Per varying: its value at each corner (double of the float), as SetupCorners::p.
  alignas(64) double varyingValues_[N > 0 ? N : 1][3][detail::kSetupLanes];
  std::array<uint32_t, kCapacity> primitiveIds_;
};

}  // namespace rast
