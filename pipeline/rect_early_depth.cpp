// One kernel source compiled for every Highway target (foreach_target re-includes this file once
// per instruction set), the target chosen with the coverage kernel (rectEarlyDepthFor).
#include "pipeline/rect_early_depth.h"

#include <algorithm>

#include "rasterizer/rect_coverage.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pipeline/rect_early_depth.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace rast {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A tile row is eight lanes: one vector where the target has eight 32-bit lanes or more (capped
// at eight), else kParts vectors side by side.
using RowTag = hn::CappedTag<int32_t, kTileSize>;
using RowTagF = hn::CappedTag<float, kTileSize>;
constexpr size_t kLanes = hn::MaxLanes(RowTag());
constexpr size_t kParts = kTileSize / kLanes;

// Edges in 32-bit lanes. Bit-exact argument: with A = a * 2^F and B = b * 2^F (an edge's change
// from one pixel centre to the next, right and down), the edge's value at column i of the k-th
// row from the first row evaluated is e + i*A + k*B (i, k in [0, 7]), e its exact int64 value at
// column 0 of that first row. When 7 * (|A| + |B|) < 2^30 those steps move it by less than 2^30,
// and e clamped to [-2^30, 2^30] gives values below 2^31 in magnitude (no int32 overflow) with
// the signs of the exact ones: unclamped they are exact; clamped from above, the exact and the
// clamped values both stay above 2^30 minus less than 2^30, so positive; clamped from below, both
// stay negative. A sample is covered when no edge is negative (the fill rule is in c), so the sign
// is all the test reads.
// The test below asks for |a|, |b| < 2^(26-F): then 7 * (|A| + |B|) < 14 * 2^26 < 2^30. It holds
// for edges shorter than 1,024 pixels along each axis in 16.8 and 262,144 in 24.4, and costs no
// division: -2^m <= v < 2^m exactly when v + 2^m, as unsigned, is below 2^(m+1), and the OR of
// such sums is below 2^(m+1) exactly when each of them is. Longer edges are evaluated in int64
// lanes by coverRect, and only their rows' bits enter the depth lanes.
constexpr int64_t kClamp = int64_t{1} << 30;
HWY_INLINE bool EdgesFitRowLanes(const std::array<EdgeFunction, 3>& edges,
                                 FixedPointFormat format) {
  const int m = 26 - format.fractionBits;
  const uint32_t bias = uint32_t{1} << m;
  uint32_t any = 0;
  for (const EdgeFunction& e : edges) any |= (uint32_t(e.a) + bias) | (uint32_t(e.b) + bias);
  return any < (bias << 1);
}

// The compare op on lanes, as depthPasses: Highway's ordered compares are false on NaN, as C++'s
// are; "not equal" is taken as "not equal to", true on NaN as != is (Highway's Ne is ordered on
// some targets).
template <CompareOp Op, class V>
HWY_INLINE auto DepthPasses(V z, V stored) {
  const RowTagF df;
  using enum CompareOp;
  if constexpr (Op == Less) return hn::Lt(z, stored);
  else if constexpr (Op == LessEqual) return hn::Le(z, stored);
  else if constexpr (Op == Equal) return hn::Eq(z, stored);
  else if constexpr (Op == Greater) return hn::Gt(z, stored);
  else if constexpr (Op == GreaterEqual) return hn::Ge(z, stored);
  else if constexpr (Op == NotEqual) return hn::Not(hn::Eq(z, stored));
  else if constexpr (Op == Never) return hn::FirstN(df, 0);
  else return hn::FirstN(df, kLanes);
}

template <class D, class M>
HWY_INLINE unsigned MaskBits(D d, M m) {
  uint8_t bits[8] = {};
  hn::StoreMaskBits(d, m, bits);
  return bits[0] & ((1u << kLanes) - 1);
}

template <CompareOp Op, bool kWrite, bool kLongEdges>
HWY_INLINE RectEarlyDepth Rows(const RasterTriangle& t, int tileX, int tileY,
                               FixedPointFormat format, float* HWY_RESTRICT stored) {
  const RowTag di;
  const RowTagF df;
  using VI = hn::Vec<RowTag>;
  using VF = hn::Vec<RowTagF>;
  const int ox = tileX * kTileSize, oy = tileY * kTileSize;
  // The bounds' rows within the tile, and their columns counted from the tile's first (lanes
  // outside the tile are never compared with them).
  const int y0 = std::max(int(t.bounds.y0) - oy, 0), y1 = std::min(int(t.bounds.y1) - oy, kTileSize);
  const int x0 = int(t.bounds.x0) - ox, x1 = int(t.bounds.x1) - ox;
  const VI lane = hn::Iota(di, 0);

  VI edge[3][kParts], down[3], columns[kParts];
  CoverageMask longEdgesCovered = 0;
  if constexpr (kLongEdges) {
    longEdgesCovered = coverRect(
        t.edges, {std::clamp(x0, 0, kTileSize), y0, std::clamp(x1, 0, kTileSize), y1}, tileX,
        tileY, format);
  } else {
    const int64_t sx = pixelCentreSubpixels(ox, format);
    const int64_t sy = pixelCentreSubpixels(oy + y0, format);
    const int64_t scale = int64_t{1} << format.fractionBits;
    for (int i = 0; i < 3; ++i) {
      const EdgeFunction& e = t.edges[i];
      const VI start = hn::Set(di, int32_t(std::clamp(e.at(sx, sy), -kClamp, kClamp)));
      const VI stepX = hn::Set(di, int32_t(int64_t{e.a} * scale));
      for (size_t p = 0; p < kParts; ++p)
        edge[i][p] = hn::Add(start, hn::Mul(hn::Add(lane, hn::Set(di, int32_t(p * kLanes))), stepX));
      down[i] = hn::Set(di, int32_t(int64_t{e.b} * scale));
    }
    for (size_t p = 0; p < kParts; ++p) {
      const VI column = hn::Add(lane, hn::Set(di, int32_t(p * kLanes)));
      columns[p] = hn::VecFromMask(
          di, hn::And(hn::Gt(column, hn::Set(di, x0 - 1)), hn::Lt(column, hn::Set(di, x1))));
    }
  }
  // Per part, the depth plane's part that does not change from row to row, at0 + ddx * dx with
  // dx = (tile's first pixel less the anchor) + column, as planeRow (tile_loop.h); per row, the
  // term ddy * dy with dy = (tile's first row less the anchor) + row, as one scalar product: the
  // same IEEE operations as a lane's, where a vector of eight terms stored and one read back per
  // row (a load from a store just made) had one of the kernel's largest sample counts after it on
  // W2 tiny-1. Both dx and dy are small integers, exact in float however they are formed.
  constexpr bool kDepth = Op != CompareOp::Always || kWrite;
  const float dx0 = float(ox - int(t.bounds.x0)), dy0 = float(oy - int(t.bounds.y0));
  VF planeAlongRow[kParts];
  if constexpr (kDepth) {
    for (size_t p = 0; p < kParts; ++p)
      planeAlongRow[p] = hn::Add(
          hn::Set(df, t.depth.at0),
          hn::Mul(hn::Set(df, t.depth.ddx),
                  hn::Add(hn::Set(df, dx0),
                          hn::ConvertTo(df, hn::Add(lane, hn::Set(di, int32_t(p * kLanes)))))));
  }
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  RectEarlyDepth out;
  for (int row = y0; row < y1; ++row) {
    const int shift = row * kTileSize;
    unsigned coveredBits = 0, passedBits = 0;
    for (size_t p = 0; p < kParts; ++p) {
      // Covered: in the bounds' columns and no edge negative, read from the sign of the edges' OR.
      hn::Mask<RowTag> inside;
      if constexpr (kLongEdges) {
        const uint8_t bits = uint8_t(longEdgesCovered >> (shift + int(p * kLanes)));
        inside = hn::LoadMaskBits(di, &bits);
      } else {
        inside = hn::MaskFromVec(hn::AndNot(
            hn::BroadcastSignBit(hn::Or(hn::Or(edge[0][p], edge[1][p]), edge[2][p])), columns[p]));
        for (int i = 0; i < 3; ++i) edge[i][p] = hn::Add(edge[i][p], down[i]);
      }
      coveredBits |= MaskBits(di, inside) << (p * kLanes);
      if constexpr (kDepth) {
        // The plane, then interpolateDepth's clamp: z > 1 -> 1, z < 0 -> +0, NaN and -0 kept.
        const float rowTerm = t.depth.ddy * (dy0 + float(row));
        const VF plane = hn::Add(planeAlongRow[p], hn::Set(df, rowTerm));
        const VF z = hn::IfThenZeroElse(hn::Lt(plane, zero),
                                        hn::IfThenElse(hn::Gt(plane, one), one, plane));
        float* s = stored + shift + p * kLanes;
        const VF before = hn::LoadU(df, s);
        const auto pass = hn::And(hn::RebindMask(df, inside), DepthPasses<Op>(z, before));
        passedBits |= MaskBits(df, pass) << (p * kLanes);
        if constexpr (kWrite) hn::StoreU(hn::IfThenElse(pass, z, before), df, s);
      }
    }
    out.covered |= CoverageMask(coveredBits) << shift;
    out.passed |= CoverageMask(passedBits) << shift;
  }
  if constexpr (!kDepth) out.passed = out.covered;
  return out;
}

template <CompareOp Op>
HWY_INLINE RectEarlyDepth ForOp(const RasterTriangle& t, int tileX, int tileY,
                                const RectDraw& draw, float* HWY_RESTRICT stored) {
  const bool longEdges = !EdgesFitRowLanes(t.edges, draw.format);
  if (draw.depthWrite)
    return longEdges ? Rows<Op, true, true>(t, tileX, tileY, draw.format, stored)
                     : Rows<Op, true, false>(t, tileX, tileY, draw.format, stored);
  return longEdges ? Rows<Op, false, true>(t, tileX, tileY, draw.format, stored)
                   : Rows<Op, false, false>(t, tileX, tileY, draw.format, stored);
}

RectEarlyDepth RectEarlyDepthRows(const RasterTriangle& t, int tileX, int tileY,
                                  const RectDraw& draw, float* HWY_RESTRICT stored) {
  using enum CompareOp;
  switch (draw.compare) {
    case Never: return ForOp<Never>(t, tileX, tileY, draw, stored);
    case Less: return ForOp<Less>(t, tileX, tileY, draw, stored);
    case Equal: return ForOp<Equal>(t, tileX, tileY, draw, stored);
    case LessEqual: return ForOp<LessEqual>(t, tileX, tileY, draw, stored);
    case Greater: return ForOp<Greater>(t, tileX, tileY, draw, stored);
    case NotEqual: return ForOp<NotEqual>(t, tileX, tileY, draw, stored);
    case GreaterEqual: return ForOp<GreaterEqual>(t, tileX, tileY, draw, stored);
    case Always: return ForOp<Always>(t, tileX, tileY, draw, stored);
  }
  return {};
}

}  // namespace HWY_NAMESPACE
}  // namespace rast
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rast {

HWY_EXPORT(RectEarlyDepthRows);

RectEarlyDepthFn rectEarlyDepthFor(const CoverageKernel& kernel) {
  if (!kernel.simd) return nullptr;
  return HWY_DISPATCH_TABLE(RectEarlyDepthRows)[highwayTableIndex(kernel.target)];
}

}  // namespace rast
#endif  // HWY_ONCE
