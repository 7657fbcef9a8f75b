// The back end: per 8x8 tile, per binned triangle in submission order: coverage of each sample
// (raster), the depth test, interpolation and the pixel shader (in 2x2 quads when the shader takes
// derivatives), then depth and colour writes (the output merger).
//
// A tile's framebuffer values are copied into a TileBuffer when its first triangle arrives and
// copied back after its last, as a GPU keeps a tile in on-chip memory: every stage then works on
// 64 lanes of L1-resident arrays in loops the compiler vectorises, whatever the tile's position.
//
// Draw state is read per (triangle, tile), never per pixel: the depth test is a function
// specialised on the compare op (chosen once per draw), and write enables and MSAA sample counts
// are tested once per triangle and tile, outside the per-lane loops.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include <immintrin.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "pipeline/bin.h"
#include "pipeline/blend.h"
#include "pipeline/front_end.h"
#include "pipeline/interpolate.h"
#include "pipeline/merge.h"
#include "pipeline/rect_early_depth.h"
#include "pipeline/shader.h"
#include "rasterizer/coverage_kernels.h"
#include "rasterizer/rect_coverage.h"
#include "rasterizer/sample_pattern.h"

namespace rast {

// The back end's helpers are forced inline so that they are compiled as part of the tile loop
// that calls them, once for the baseline target and once for AVX2 (rasterizeTilesAvx2 below).
#define RAST_TILE_INLINE [[gnu::always_inline]] inline
// The same for the tile loop's lambdas: one GCC compiles on its own is built for the baseline
// target only, whatever its caller's (writePending was, and took 7 % of W3's frame in SSE2).
#define RAST_TILE_LAMBDA __attribute__((always_inline))

inline constexpr int kTileLanes = kTileSize * kTileSize;

template <class T>
using TileLanes = std::array<T, kTileLanes>;

// The pixel shader's colours for a tile, one array per channel, so that packing them to RGBA8
// runs over whole rows of lanes in a loop the compiler vectorises. Lanes that were not shaded
// hold stale (or the initial zero) values: they are packed and never written.
struct ShadedColors {
  TileLanes<float> r{}, g{}, b{}, a{};

  void set(int lane, glm::vec4 c) {
    r[lane] = c.r;
    g[lane] = c.g;
    b[lane] = c.b;
    a[lane] = c.a;
  }
  glm::vec4 at(int lane) const { return {r[lane], g[lane], b[lane], a[lane]}; }
};

// A triangle's fragments in a tile that passed the depth test and wait to be shaded, where the
// back end shades only the fragments a tile keeps (rasterizeTile's deferShading).
struct DeferredShading {
  uint32_t triangle;  // its id (SetupTriangles)
  CoverageMask passed;
};

// A tile's copy of the framebuffer: per sample plane, 64 lanes in coverage-bit order; and the
// per-triangle work arrays, kept here so that a task allocates them once for all its tiles.
struct TileBuffer {
  std::array<TileLanes<float>, kMaxSamples> depth;
  std::array<TileLanes<PackedColor>, kMaxSamples> color;
  TileLanes<uint32_t> counts;
  ShadedColors shaded;
  TileLanes<PackedColor> packed{};
  std::vector<uint32_t> mergedEntries;  // TileBins::entries' scratch
  // rasterizeTile's list of fragments waiting to be shaded, when it defers shading: a tile's
  // triangles while they fit (W1: 24 a tile on average), else in parts (the fragments listed are
  // then shaded before the rest are listed, which shades more than once where later ones win).
  static constexpr int kMaxDeferred = 64;
  std::array<DeferredShading, kMaxDeferred> deferred;
  int deferredCount = 0;
};

// Bounds of the depth values stored in a tile, so a triangle whose depth range lies entirely on
// the failing side of them fails for the whole tile without per-sample tests (and entirely on
// the passing side, passes without them). Exact, not approximate: the plane is evaluated in float
// as (at0 + ddx*dx) + ddy*dy, and every step of that is monotonic in dx and in dy, so the float
// value at any sample of the tile lies between the float values at the tile's corner samples.
// Bounds may be wider than the stored values (after a write they are widened by the writing
// triangle's range instead of recomputed): wider bounds decide less, never wrongly.
// A NaN stored depth (only a NaN clear value makes one) fails every ordered compare, so it
// cannot spoil "all fail" but forbids "all pass".
struct TileDepthBounds {
  float min = 0, max = 0;
  bool hasNaN = false;
  bool valid = false;
};

// The bounds of the first `samples` planes of a tile's depth. All 64 lanes: the padding lanes of
// an edge tile hold one of the tile's own stored values (see load), so they cannot widen the
// bounds beyond what the tile holds. One accumulator per column, four columns to an SSE2 register:
// minps(d, m) is d < m ? d : m and maxps(d, m) is d > m ? d : m, so a NaN lane (it fails both
// compares) leaves them alone and sets hasNaN. The set's min and max do not depend on the order,
// except for the sign of a zero, which no compare sees. Intrinsics, not a loop left to the
// compiler: GCC turns that loop into scalar conditional moves under -fno-trapping-math.
RAST_TILE_INLINE TileDepthBounds tileDepthBounds(const std::array<TileLanes<float>, kMaxSamples>& depth,
                                                 int samples) {
  __m128 mnLeft = _mm_set1_ps(std::numeric_limits<float>::infinity()), mnRight = mnLeft;
  __m128 mxLeft = _mm_set1_ps(-std::numeric_limits<float>::infinity()), mxRight = mxLeft;
  __m128 nan = _mm_setzero_ps();
  for (int s = 0; s < samples; ++s)
    for (int ly = 0; ly < kTileSize; ++ly) {
      const __m128 left = _mm_loadu_ps(&depth[s][ly * kTileSize]);
      const __m128 right = _mm_loadu_ps(&depth[s][ly * kTileSize + 4]);
      nan = _mm_or_ps(nan, _mm_or_ps(_mm_cmpunord_ps(left, left), _mm_cmpunord_ps(right, right)));
      mnLeft = _mm_min_ps(left, mnLeft);
      mnRight = _mm_min_ps(right, mnRight);
      mxLeft = _mm_max_ps(left, mxLeft);
      mxRight = _mm_max_ps(right, mxRight);
    }
  // Across the eight columns, by halves: no accumulator holds a NaN (minps and maxps keep their
  // second operand when the first is NaN), so any order gives the set's min and max.
  __m128 mn = _mm_min_ps(mnLeft, mnRight), mx = _mm_max_ps(mxLeft, mxRight);
  mn = _mm_min_ps(mn, _mm_shuffle_ps(mn, mn, _MM_SHUFFLE(1, 0, 3, 2)));
  mx = _mm_max_ps(mx, _mm_shuffle_ps(mx, mx, _MM_SHUFFLE(1, 0, 3, 2)));
  mn = _mm_min_ps(mn, _mm_shuffle_ps(mn, mn, _MM_SHUFFLE(2, 3, 0, 1)));
  mx = _mm_max_ps(mx, _mm_shuffle_ps(mx, mx, _MM_SHUFFLE(2, 3, 0, 1)));
  TileDepthBounds b{_mm_cvtss_f32(mn), _mm_cvtss_f32(mx), _mm_movemask_ps(nan) != 0, true};
  return b;
}

constexpr bool isOrderedCompare(CompareOp op) {
  return op == CompareOp::Less || op == CompareOp::LessEqual || op == CompareOp::Greater ||
         op == CompareOp::GreaterEqual;
}

inline bool allFail(CompareOp op, float triMin, float triMax, const TileDepthBounds& b) {
  switch (op) {
    case CompareOp::Less: return triMin >= b.max;
    case CompareOp::LessEqual: return triMin > b.max;
    case CompareOp::Greater: return triMax <= b.min;
    case CompareOp::GreaterEqual: return triMax < b.min;
    default: return false;
  }
}

inline bool allPass(CompareOp op, float triMin, float triMax, const TileDepthBounds& b) {
  if (b.hasNaN) return false;
  switch (op) {
    case CompareOp::Less: return triMax < b.min;
    case CompareOp::LessEqual: return triMax <= b.min;
    case CompareOp::Greater: return triMin > b.max;
    case CompareOp::GreaterEqual: return triMin >= b.max;
    default: return false;
  }
}

// The compare op on four lanes, as a lane mask: SSE2's ordered compares are false on NaN, as C++'s
// <, <=, ==, >, >= are; its "not equal" is true on NaN, as != is. So the lanes agree with
// depthPasses bit for bit (tests/merge_test.cpp). SSE2 is part of the x86-64 baseline: no
// dispatch is needed, and both builds of the tile loop use the same instructions.
template <CompareOp Op>
RAST_TILE_INLINE int depthPassBits4(__m128 z, __m128 stored) {
  using enum CompareOp;
  if constexpr (Op == Less) return _mm_movemask_ps(_mm_cmplt_ps(z, stored));
  else if constexpr (Op == LessEqual) return _mm_movemask_ps(_mm_cmple_ps(z, stored));
  else if constexpr (Op == Equal) return _mm_movemask_ps(_mm_cmpeq_ps(z, stored));
  else if constexpr (Op == Greater) return _mm_movemask_ps(_mm_cmpgt_ps(z, stored));
  else if constexpr (Op == GreaterEqual) return _mm_movemask_ps(_mm_cmpge_ps(z, stored));
  else if constexpr (Op == NotEqual) return _mm_movemask_ps(_mm_cmpneq_ps(z, stored));
  else if constexpr (Op == Never) return 0;
  else return 0xf;
}

// The depth test of 64 lanes, specialised on the compare op; returns the lanes of `mask` that pass.
// Only rows [rowBegin, rowEnd) are read: the rows `mask` touches. The pass bits are formed in
// registers, eight per row, not stored as bytes and read back as a word: a load is not forwarded
// from eight separate byte stores, and that stall cost 8 % of W2 tiny-1's tile loop.
template <CompareOp Op>
RAST_TILE_INLINE CoverageMask depthTestLanes(const TileLanes<float>& z, const TileLanes<float>& stored,
                            CoverageMask mask, int rowBegin, int rowEnd) {
  CoverageMask pass = 0;
  for (int row = rowBegin; row < rowEnd; ++row) {
    const float* zr = &z[size_t(row) * kTileSize];
    const float* sr = &stored[size_t(row) * kTileSize];
    const int bits = depthPassBits4<Op>(_mm_loadu_ps(zr), _mm_loadu_ps(sr)) |
                     depthPassBits4<Op>(_mm_loadu_ps(zr + 4), _mm_loadu_ps(sr + 4)) << 4;
    pass |= CoverageMask(unsigned(bits)) << (kTileSize * row);
  }
  return pass & mask;
}

// The same tests by a switch, so that the tile loop inlines them (and compiles them for its target).
RAST_TILE_INLINE CoverageMask depthTestInline(CompareOp op, const TileLanes<float>& z,
                                              const TileLanes<float>& stored, CoverageMask mask,
                                              int rowBegin, int rowEnd) {
  using enum CompareOp;
  switch (op) {
    case Never: return depthTestLanes<Never>(z, stored, mask, rowBegin, rowEnd);
    case Less: return depthTestLanes<Less>(z, stored, mask, rowBegin, rowEnd);
    case Equal: return depthTestLanes<Equal>(z, stored, mask, rowBegin, rowEnd);
    case LessEqual: return depthTestLanes<LessEqual>(z, stored, mask, rowBegin, rowEnd);
    case Greater: return depthTestLanes<Greater>(z, stored, mask, rowBegin, rowEnd);
    case NotEqual: return depthTestLanes<NotEqual>(z, stored, mask, rowBegin, rowEnd);
    case GreaterEqual: return depthTestLanes<GreaterEqual>(z, stored, mask, rowBegin, rowEnd);
    case Always: return mask;
  }
  return mask;
}

// The depth test of the few covered pixels of `mask`, one at a time (rasterizeTile's fewPixels):
// the depth of each at (dx0 + column, dy0 + row) by interpolateDepth, quantised by `quantize`
// when there is one, into `z`, then compared by depthPasses. The lanes agree with these bit for
// bit, so the result is what depthLanes, quantizeLanes and depthTestLanes give those pixels.
// Returns the pixels that pass; `lo` and `hi` get the range of their depths, NaN in `lo` if one
// is NaN. Specialised on the compare op, so no pixel tests draw state.
struct FewPixelsPassed {
  CoverageMask passed = 0;
  float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
};
template <CompareOp Op, int N>
RAST_TILE_INLINE FewPixelsPassed depthTestFewPixels(const SetupTriangle<N>& t, CoverageMask mask,
                                                    float dx0, float dy0, float (*quantize)(float),
                                                    const TileLanes<float>& stored,
                                                    TileLanes<float>& z) {
  for (CoverageMask m = mask; m; m &= m - 1) {
    const int i = std::countr_zero(m);
    z[i] = interpolateDepth(t, dx0 + float(i % kTileSize), dy0 + float(i / kTileSize));
  }
  if (quantize)
    for (CoverageMask m = mask; m; m &= m - 1) {
      const int i = std::countr_zero(m);
      z[i] = quantize(z[i]);
    }
  FewPixelsPassed r;
  bool nan = false;
  for (CoverageMask m = mask; m; m &= m - 1) {
    const int i = std::countr_zero(m);
    if (!depthPasses<Op>(z[i], stored[i])) continue;
    r.passed |= CoverageMask{1} << i;
    r.lo = std::min(r.lo, z[i]);
    r.hi = std::max(r.hi, z[i]);
    nan |= z[i] != z[i];
  }
  if (nan) r.lo = std::numeric_limits<float>::quiet_NaN();
  return r;
}

template <int N>
RAST_TILE_INLINE FewPixelsPassed depthTestFewPixelsInline(CompareOp op, const SetupTriangle<N>& t,
                                                          CoverageMask mask, float dx0, float dy0,
                                                          float (*quantize)(float),
                                                          const TileLanes<float>& stored,
                                                          TileLanes<float>& z) {
  using enum CompareOp;
  switch (op) {
    case Never: return depthTestFewPixels<Never>(t, mask, dx0, dy0, quantize, stored, z);
    case Less: return depthTestFewPixels<Less>(t, mask, dx0, dy0, quantize, stored, z);
    case Equal: return depthTestFewPixels<Equal>(t, mask, dx0, dy0, quantize, stored, z);
    case LessEqual: return depthTestFewPixels<LessEqual>(t, mask, dx0, dy0, quantize, stored, z);
    case Greater: return depthTestFewPixels<Greater>(t, mask, dx0, dy0, quantize, stored, z);
    case NotEqual: return depthTestFewPixels<NotEqual>(t, mask, dx0, dy0, quantize, stored, z);
    case GreaterEqual:
      return depthTestFewPixels<GreaterEqual>(t, mask, dx0, dy0, quantize, stored, z);
    case Always: return depthTestFewPixels<Always>(t, mask, dx0, dy0, quantize, stored, z);
  }
  return {};
}

// What the back end does, fixed for the whole draw.
struct BackEndConfig {
  FixedPointFormat format;
  CoverageKernel kernel;
  RectEarlyDepthFn rectEarlyDepth = nullptr;  // the kernel's target's (null: the scalar reference)
  SamplePattern samples;
  CompareOp compare = CompareOp::Always;  // Always: no test
  bool depthWrite = false;
  bool colorWrite = false;
  bool earlyDepth = true;
  // Blending or a partial write mask: the stored colour takes part, per sample.
  bool colorMerge = false;
  BlendState blend;
  uint8_t colorWriteMask = kWriteAll;
  RasterMode rasterMode = RasterMode::FixedPoint;
  // Depth as the depth buffer stores it (depth_format.h); null for 32-bit float, which keeps it.
  void (*quantizeDepthLanes)(TileLanes<float>& z, int rowBegin, int rowEnd) = nullptr;
  float (*quantize)(float z) = nullptr;
  // Shade only the fragments a tile keeps, where that changes no bit (rasterizeTile).
  bool deferShading = true;
  // The draw's load op: every tile starts from these values instead of the framebuffer's, and
  // every tile, touched or not, is stored (ClearValues).
  bool clearFirst = false;
  PackedColor clearColor = 0;
  float clearDepth = 0;
  // Framebuffer planes (sample-major) and size.
  MergeTarget target;
  int width = 0, height = 0;

  bool depthRead() const { return compare != CompareOp::Always; }
  bool depthUsed() const { return depthRead() || depthWrite; }
};

// A plane over a row of a tile, four lanes a half: the part of (at0 + ddx*dx) + ddy*dy that does
// not change from row to row, at the columns dx = dx0 + 0..3 and dx0 + 4..7. The float sums and
// products are those interpolateDepth and interpolateVaryings make at each lane (SSE2's are IEEE
// single precision, and -ffp-contract=off keeps FMA out), so every lane gets their bits.
struct PlaneRow {
  __m128 left, right;  // at0 + ddx*dx
  __m128 ddy;
};
RAST_TILE_INLINE PlaneRow planeRow(const PlaneEquation& p, float dx0) {
  const __m128 dx = _mm_set1_ps(dx0);
  const __m128 at0 = _mm_set1_ps(p.at0), ddx = _mm_set1_ps(p.ddx);
  return {_mm_add_ps(at0, _mm_mul_ps(ddx, _mm_add_ps(dx, _mm_setr_ps(0, 1, 2, 3)))),
          _mm_add_ps(at0, _mm_mul_ps(ddx, _mm_add_ps(dx, _mm_setr_ps(4, 5, 6, 7)))),
          _mm_set1_ps(p.ddy)};
}

// interpolateDepth's clamp to [0, 1] on four lanes: z < 0 ? 0 : (z > 1 ? 1 : z), by compares and
// masks, not min/max (which would turn -0 into +0, where the clamp keeps -0, and NaN into a bound).
RAST_TILE_INLINE __m128 clampDepth4(__m128 z) {
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 above = _mm_cmpgt_ps(z, one);
  const __m128 upper = _mm_or_ps(_mm_and_ps(above, one), _mm_andnot_ps(above, z));
  return _mm_andnot_ps(_mm_cmplt_ps(z, _mm_setzero_ps()), upper);
}

// Depth of the triangle at the lanes of rows [rowBegin, rowEnd) of sample s: interpolateDepth at
// each, so the per-sample and per-pixel paths agree bit for bit (tests/interpolation_test.cpp).
// Written in SSE2 a row at a time: the loop GCC vectorised from interpolateDepth per lane spent
// most of its instructions on each lane's column and row (README, "Tile buffers").
template <int N>
RAST_TILE_INLINE void depthLanes(const SetupTriangle<N>& t, int x0, int y0, float offsetX, float offsetY,
                int rowBegin, int rowEnd, TileLanes<float>& z) {
  const float dx0 = float(x0 - t.bounds.x0) + offsetX, dy0 = float(y0 - t.bounds.y0) + offsetY;
  const PlaneRow p = planeRow(t.depth, dx0);
  for (int row = rowBegin; row < rowEnd; ++row) {
    const __m128 down = _mm_mul_ps(p.ddy, _mm_set1_ps(dy0 + float(row)));
    float* out = &z[size_t(row) * kTileSize];
    _mm_storeu_ps(out, clampDepth4(_mm_add_ps(p.left, down)));
    _mm_storeu_ps(out + 4, clampDepth4(_mm_add_ps(p.right, down)));
  }
}

// The depth buffer format's value of each lane (depth_format.h), rows [rowBegin, rowEnd).
template <DepthFormat F>
void quantizeLanes(TileLanes<float>& z, int rowBegin, int rowEnd) {
  for (int i = rowBegin * kTileSize; i < rowEnd * kTileSize; ++i) z[i] = quantizeDepth<F>(z[i]);
}

// Shaders that declare `static constexpr bool kDerivatives = true` run on 2x2 quads.
template <class PS>
constexpr bool kTakesDerivatives = requires { requires PS::kDerivatives; };

// Shaders that declare `static constexpr bool kPerTriangle = true` return the same result for
// every fragment of a triangle (they read only primitiveId and frontFacing): they run once per
// triangle and tile, and the colour is packed once. The statistics still count one invocation per
// pixel, the work the pipeline stands for, so that no counter depends on this shortcut.
template <class PS>
constexpr bool kShadesPerTriangle = requires { requires PS::kPerTriangle; };

// Shaders that declare `static constexpr bool kSideEffects = true` (shader.h) run once per passing
// fragment, as it passes.
template <class PS>
constexpr bool kHasSideEffects = requires { requires PS::kSideEffects; };

// Shaders that declare `static constexpr bool kWholeRows = true` (shader.h) run on every lane of
// the rows a triangle covers, in a loop the compiler vectorises; each lane's result has the bits
// a run on that lane alone gives (the same IEEE operations, no contraction, -fno-math-errno lets
// sqrt be the vector instruction).
template <class PS>
constexpr bool kShadesWholeRows =
    requires { requires PS::kWholeRows; } && !PS::kMayDiscard && !kTakesDerivatives<PS>;

// The rows [begin, end) of a tile that a non-empty mask touches.
struct RowRange {
  int begin, end;
};
RAST_TILE_INLINE RowRange coveredRows(CoverageMask mask) {
  return {std::countr_zero(mask) / kTileSize,
          (kTileLanes - 1 - std::countl_zero(mask)) / kTileSize + 1};
}

// The varyings of rows [rowBegin, rowEnd) of a tile, lane by lane: interpolateVaryings at each
// lane (dx, dy are small integers, exact in float either way), a row at a time in SSE2 as
// depthLanes: v/w at the lane times 1 / (1/w at the lane), IEEE division included.
template <int N>
using TileVaryings = std::array<TileLanes<float>, N>;

// Rows [rowBegin, rowEnd) of the varyings, handed to store(row, k, left, right) as two
// four-lane halves, so that every caller gets the same bits.
template <int N, class Store>
RAST_TILE_INLINE void forEachInterpolatedRow(const SetupTriangle<N>& t, int x0, int y0,
                                             int rowBegin, int rowEnd, Store&& store) {
  if constexpr (N > 0) {
    const float dx0 = float(x0 - t.bounds.x0), dy0 = float(y0 - t.bounds.y0);
    const PlaneRow invW = planeRow(t.invW, dx0);
    std::array<PlaneRow, N> overW;
    for (int k = 0; k < N; ++k) overW[k] = planeRow(t.varyingsOverW[k], dx0);
    const __m128 one = _mm_set1_ps(1.0f);
    for (int row = rowBegin; row < rowEnd; ++row) {
      const __m128 dy = _mm_set1_ps(dy0 + float(row));
      const __m128 wLeft = _mm_div_ps(one, _mm_add_ps(invW.left, _mm_mul_ps(invW.ddy, dy)));
      const __m128 wRight = _mm_div_ps(one, _mm_add_ps(invW.right, _mm_mul_ps(invW.ddy, dy)));
      for (int k = 0; k < N; ++k) {
        const __m128 down = _mm_mul_ps(overW[k].ddy, dy);
        store(row, k, _mm_mul_ps(_mm_add_ps(overW[k].left, down), wLeft),
              _mm_mul_ps(_mm_add_ps(overW[k].right, down), wRight));
      }
    }
  }
}

template <int N>
RAST_TILE_INLINE void interpolateRows(const SetupTriangle<N>& t, int x0, int y0, int rowBegin,
                                      int rowEnd, TileVaryings<N>& out) {
  forEachInterpolatedRow<N>(t, x0, y0, rowBegin, rowEnd,
                            [&](int row, int k, __m128 left, __m128 right) RAST_TILE_LAMBDA {
                              float* o = &out[k][size_t(row) * kTileSize];
                              _mm_storeu_ps(o, left);
                              _mm_storeu_ps(o + 4, right);
                            });
}

// interpolateRows at the lanes of `lanes` only, merged into `out`, whose other lanes keep their
// values: the varyings of each visible fragment of a tile gathered from the triangles that own
// them, for one shading pass over the tile (shadeDeferred).
template <int N>
RAST_TILE_INLINE void interpolateRowsWhere(const SetupTriangle<N>& t, int x0, int y0,
                                           CoverageMask lanes, TileVaryings<N>& out) {
  const __m128i leftBits = _mm_setr_epi32(1, 2, 4, 8), rightBits = _mm_setr_epi32(16, 32, 64, 128);
  const RowRange rows = coveredRows(lanes);
  forEachInterpolatedRow<N>(
      t, x0, y0, rows.begin, rows.end,
      [&](int row, int k, __m128 left, __m128 right) RAST_TILE_LAMBDA {
        const __m128i rowBits = _mm_set1_epi32(int(lanes >> (kTileSize * row) & 0xff));
        const __m128 takeLeft = _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(rowBits, leftBits), leftBits));
        const __m128 takeRight = _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(rowBits, rightBits), rightBits));
        float* o = &out[k][size_t(row) * kTileSize];
        _mm_storeu_ps(o, _mm_or_ps(_mm_and_ps(takeLeft, left), _mm_andnot_ps(takeLeft, _mm_loadu_ps(o))));
        _mm_storeu_ps(o + 4, _mm_or_ps(_mm_and_ps(takeRight, right),
                                       _mm_andnot_ps(takeRight, _mm_loadu_ps(o + 4))));
      });
}

// A kShadesPerTriangle shader's one run for a triangle in a tile, at pixel `bit` of the tile.
template <PixelShader PS, int N>
RAST_TILE_INLINE PixelResult shadeOncePerTriangle(const SetupTriangle<N>& t, int x0, int y0,
                                                  int bit, const PS& shader) {
  static_assert(N == 0, "a shader run once per triangle reads no varyings");
  Fragment<N> fragment;
  fragment.x = x0 + bit % kTileSize;
  fragment.y = y0 + bit / kTileSize;
  fragment.depth = interpolateDepth(t, float(fragment.x - t.bounds.x0),
                                    float(fragment.y - t.bounds.y0));
  fragment.frontFacing = t.frontFacing();
  fragment.primitiveId = t.primitiveId();
  return shader(fragment);
}

// RGBA8 of the lanes of `lanes` (packColor): lane by lane, since shaded triangles are mostly small
// (W1: a few pixels per row), and GCC does not vectorise the clamp's float compares.
RAST_TILE_INLINE void packLanes(const ShadedColors& c, CoverageMask lanes, TileLanes<PackedColor>& out) {
  for (CoverageMask m = lanes; m; m &= m - 1) {
    const int i = std::countr_zero(m);
    out[i] = packColor(c.at(i));
  }
}

// One channel of colorByte on four lanes: maxps(v, 0) then minps(that, 1), times 255 plus a half,
// truncated (every value lies in [0.5, 255.5], where cvttps2dq truncates as the conversion to
// uint32_t does).
RAST_TILE_INLINE __m128i colorBytes4(__m128 v) {
  const __m128 clamped = _mm_min_ps(_mm_max_ps(v, _mm_setzero_ps()), _mm_set1_ps(1.0f));
  return _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(clamped, _mm_set1_ps(255.0f)), _mm_set1_ps(0.5f)));
}

// RGBA8 of every lane of rows [rowBegin, rowEnd) (packColor's bits), four lanes at a time, for
// shaders run on whole rows.
RAST_TILE_INLINE void packRowColors(const ShadedColors& c, int rowBegin, int rowEnd,
                                    TileLanes<PackedColor>& out) {
  for (int i = rowBegin * kTileSize; i < rowEnd * kTileSize; i += 4) {
    const __m128i rgba = _mm_or_si128(
        _mm_or_si128(colorBytes4(_mm_loadu_ps(&c.r[i])),
                     _mm_slli_epi32(colorBytes4(_mm_loadu_ps(&c.g[i])), 8)),
        _mm_or_si128(_mm_slli_epi32(colorBytes4(_mm_loadu_ps(&c.b[i])), 16),
                     _mm_slli_epi32(colorBytes4(_mm_loadu_ps(&c.a[i])), 24)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&out[i]), rgba);
  }
}

// A kWholeRows shader over every lane of rows `rows`, each lane's varyings from `varyings` and its
// depth, facing and primitive id from triangleAt(bit), the colours stored in `out`.
template <PixelShader PS, int N, class TriangleAt>
RAST_TILE_INLINE void shadeWholeRows(RowRange rows, int x0, int y0, const TileVaryings<N>& varyings,
                                     TriangleAt&& triangleAt, const PS& shader, ShadedColors& out) {
  for (int row = rows.begin; row < rows.end; ++row)
    for (int lx = 0; lx < kTileSize; ++lx) {
      const int bit = row * kTileSize + lx;
      const SetupTriangle<N>& t = triangleAt(bit);
      Fragment<N> fragment;
      for (int k = 0; k < N; ++k) fragment.varyings[k] = varyings[k][bit];
      fragment.x = x0 + lx;
      fragment.y = y0 + row;
      fragment.depth = interpolateDepth(t, float(fragment.x - t.bounds.x0),
                                        float(fragment.y - t.bounds.y0));
      fragment.frontFacing = t.frontFacing();
      fragment.primitiveId = t.primitiveId();
      const glm::vec4 c = shader(fragment).color;
      out.r[bit] = c.r;
      out.g[bit] = c.g;
      out.b[bit] = c.b;
      out.a[bit] = c.a;
    }
}

// Runs the pixel shader on the pixels of `pixels` and stores their colours in `out`; returns the
// pixels that were not discarded. (The caller counts the invocations; quads count their helper
// lanes in `stats`.)
template <PixelShader PS, int N>
RAST_TILE_INLINE CoverageMask shadePixels(const SetupTriangle<N>& t, int x0, int y0, CoverageMask pixels,
                         const PS& shader, ShadedColors& out, PipelineStatistics& stats) {
  CoverageMask kept = pixels;
  auto shadeOne = [&](int bit, Fragment<N>& fragment) RAST_TILE_LAMBDA {
    const int px = x0 + bit % kTileSize, py = y0 + bit / kTileSize;
    const float dx = float(px - t.bounds.x0), dy = float(py - t.bounds.y0);
    fragment.x = px;
    fragment.y = py;
    fragment.depth = interpolateDepth(t, dx, dy);
    fragment.frontFacing = t.frontFacing();
    fragment.primitiveId = t.primitiveId();
    const PixelResult result = shader(fragment);
    if constexpr (PS::kMayDiscard) {
      if (result.discard) {
        kept &= ~(CoverageMask{1} << bit);
        return;
      }
    }
    out.set(bit, result.color);
  };

  if constexpr (kTakesDerivatives<PS>) {
    // Quads: every lane of a quad with a covered pixel is interpolated, the uncovered ones as
    // helper lanes, so differences across the quad give the derivatives (coarse, as Direct3D's
    // ddx/ddy: one per quad, from its top-left pixel to its right and lower neighbours). Helper
    // lanes are never shaded or written.
    constexpr CoverageMask kQuad = 0b11 | (0b11ull << kTileSize);
    for (int qy = 0; qy < kTileSize; qy += 2)
      for (int qx = 0; qx < kTileSize; qx += 2) {
        const int base = qy * kTileSize + qx;
        const CoverageMask lanes = pixels & (kQuad << base);
        if (!lanes) continue;
        std::array<Varyings<N>, 4> v;
        for (int k = 0; k < 4; ++k) {
          const float dx = float(x0 + qx + (k & 1) - t.bounds.x0);
          const float dy = float(y0 + qy + (k >> 1) - t.bounds.y0);
          interpolateVaryings<N>(t, dx, dy, v[k]);
        }
        Fragment<N> fragment;
        for (int i = 0; i < N; ++i) {
          fragment.ddx[i] = v[1][i] - v[0][i];
          fragment.ddy[i] = v[2][i] - v[0][i];
        }
        stats.pixelHelperLanes += uint64_t(4 - popcount64(lanes));
        for (int k = 0; k < 4; ++k) {
          const int bit = base + (k & 1) + (k >> 1) * kTileSize;
          if (!(lanes >> bit & 1)) continue;
          fragment.varyings = v[k];
          shadeOne(bit, fragment);
        }
      }
  } else if constexpr (kShadesWholeRows<PS>) {
    const RowRange rows = coveredRows(pixels);
    TileVaryings<N> varyings;
    interpolateRows<N>(t, x0, y0, rows.begin, rows.end, varyings);
    shadeWholeRows<PS, N>(
        rows, x0, y0, varyings,
        [&](int) RAST_TILE_LAMBDA -> const SetupTriangle<N>& { return t; }, shader, out);
  } else {
    const RowRange rows = coveredRows(pixels);
    TileVaryings<N> varyings;
    interpolateRows<N>(t, x0, y0, rows.begin, rows.end, varyings);
    for (CoverageMask m = pixels; m; m &= m - 1) {
      const int bit = std::countr_zero(m);
      Fragment<N> fragment;
      for (int k = 0; k < N; ++k) fragment.varyings[k] = varyings[k][bit];
      shadeOne(bit, fragment);
    }
  }
  return kept;
}

// Lanes of `mask` written from a source of lanes: another tile's lanes (copyLanesWhere) or one
// value in every lane (fillLanesWhere). Few lanes (small triangles, the usual case) go lane by
// lane over the set bits; more, row by row over the rows they touch, each row one select of its
// eight lanes (a row-by-row write for every mask measured slower on W1 and W4; lane by lane for
// dense masks left W2 tiny-1000's loop-exit branches and single-lane stores the largest cost of
// its back end). Either way each lane of the mask gets the source's bits and every other lane
// keeps its own.
inline constexpr int kSparseLanes = 8;
// A row of eight 32-bit lanes as a GCC/Clang vector: one AVX2 register in the AVX2 tile loop, two
// SSE2 ones in the baseline's.
using RowBits = int32_t __attribute__((vector_size(32)));

template <class T>
struct LanesOf {
  const TileLanes<T>& lanes;
  RAST_TILE_INLINE T lane(int i) const { return lanes[size_t(i)]; }
  RAST_TILE_INLINE void row(int r, RowBits& bits) const {
    std::memcpy(&bits, lanes.data() + r * kTileSize, sizeof(bits));
  }
};
template <class T>
struct OneValue {
  T value;
  RAST_TILE_INLINE T lane(int) const { return value; }
  RAST_TILE_INLINE void row(int, RowBits& bits) const {
    bits = RowBits{} + std::bit_cast<int32_t>(value);
  }
};

template <class T, class Source>
RAST_TILE_INLINE void writeLanesWhere(CoverageMask mask, const Source& source, TileLanes<T>& to) {
  static_assert(sizeof(T) == sizeof(int32_t) && std::is_trivially_copyable_v<T>);
  if (popcount64(mask) <= kSparseLanes) {
    for (CoverageMask m = mask; m; m &= m - 1) {
      const int bit = std::countr_zero(m);
      to[size_t(bit)] = source.lane(bit);
    }
    return;
  }
  const RowBits laneBit = {1, 2, 4, 8, 16, 32, 64, 128};
  const RowRange rows = coveredRows(mask);
  for (int row = rows.begin; row < rows.end; ++row) {
    T* out = to.data() + row * kTileSize;
    RowBits before, after;
    std::memcpy(&before, out, sizeof(before));
    source.row(row, after);
    // All ones in the lanes whose bit of the row is set.
    const RowBits take = ((RowBits{} + int32_t(mask >> (row * kTileSize) & 0xffu)) & laneBit) != 0;
    const RowBits written = (after & take) | (before & ~take);
    std::memcpy(out, &written, sizeof(written));
  }
}

// to[i] = from[i] for the lanes i of `mask`.
template <class T>
RAST_TILE_INLINE void copyLanesWhere(CoverageMask mask, const TileLanes<T>& from, TileLanes<T>& to) {
  if (mask == kFullMask) {
    to = from;
    return;
  }
  writeLanesWhere(mask, LanesOf<T>{from}, to);
}

template <class T>
RAST_TILE_INLINE void fillLanesWhere(CoverageMask mask, T value, TileLanes<T>& to) {
  if (mask == kFullMask) {
    to.fill(value);
    return;
  }
  writeLanesWhere(mask, OneValue<T>{value}, to);
}

// One tile: its framebuffer values in, every binned triangle in order, the values out.
// kSamples: the draw's samples per pixel when the loop is built for one count (1: no MSAA, so
// that every per-sample loop and array below folds away), 0 when it takes any.
template <PixelShader PS, int N, int kSamples>
RAST_TILE_INLINE void rasterizeTile(int tileX, int tileY, std::span<const uint32_t> bin,
                   const SetupTriangles<N>& triangles, const PS& shader,
                   const BackEndConfig& cfg, TileBuffer& tile, PipelineStatistics& stats) {
  if (bin.empty()) return;  // (with the load op rasterizeTileRange fills untouched tiles)
  const int S = kSamples ? kSamples : cfg.samples.count;
  const int x0 = tileX * kTileSize, y0 = tileY * kTileSize;
  const int cols = std::min(kTileSize, cfg.width - x0), rows = std::min(kTileSize, cfg.height - y0);
  const size_t planeSize = size_t(cfg.width) * size_t(cfg.height);
  const bool depthRead = cfg.depthRead();
  const bool depthUsed = cfg.depthUsed();
  const bool counting = cfg.target.counts != nullptr;
  const MergeTarget& target = cfg.target;

  // Lanes beyond the framebuffer's edge are never covered (bounds stop at the edge) and never
  // stored; they hold a copy of lane 0, a value of the tile's own, so that they cannot widen the
  // tile's depth bounds.
  auto load = [&](auto* plane, auto& lanes, auto pad) RAST_TILE_LAMBDA {
    for (int ly = 0; ly < rows; ++ly) {
      const auto* row = plane + size_t(y0 + ly) * cfg.width + x0;
      if (cols == kTileSize) std::memcpy(&lanes[ly * kTileSize], row, sizeof(lanes[0]) * kTileSize);
      else std::memcpy(&lanes[ly * kTileSize], row, sizeof(lanes[0]) * size_t(cols));
    }
    if (cols < kTileSize || rows < kTileSize)
      for (int ly = 0; ly < kTileSize; ++ly)
        for (int lx = 0; lx < kTileSize; ++lx)
          if (lx >= cols || ly >= rows) lanes[ly * kTileSize + lx] = pad(lanes);
  };
  auto store = [&](auto* plane, const auto& lanes) RAST_TILE_LAMBDA {
    for (int ly = 0; ly < rows; ++ly) {
      auto* row = plane + size_t(y0 + ly) * cfg.width + x0;
      if (cols == kTileSize) std::memcpy(row, &lanes[ly * kTileSize], sizeof(lanes[0]) * kTileSize);
      else std::memcpy(row, &lanes[ly * kTileSize], sizeof(lanes[0]) * size_t(cols));
    }
  };
  // With the load op every lane, padding included, holds the clear value: what load gives a
  // tile the clear filled (its padding copies lane 0). The tile is stored whether or not a
  // triangle writes it.
  if (depthUsed)
    for (int s = 0; s < S; ++s) {
      if (cfg.clearFirst) tile.depth[s].fill(cfg.clearDepth);
      else load(target.depth + s * planeSize, tile.depth[s], [](auto& l) { return l[0]; });
    }
  if (cfg.colorWrite)
    for (int s = 0; s < S; ++s) {
      if (cfg.clearFirst) tile.color[s].fill(cfg.clearColor);
      else load(target.color + s * planeSize, tile.color[s], [](auto& l) { return l[0]; });
    }
  if (counting) load(target.counts, tile.counts, [](auto& l) { return l[0]; });

  const bool shade = cfg.colorWrite || PS::kMayDiscard;
  // Depth tested before shading: always when no shader runs, else when early depth is on.
  const bool earlyTest = depthRead && (cfg.earlyDepth || !shade);
  // Hidden-surface removal before shading, as a tile-based deferred GPU does it: where a pixel
  // keeps the colour of the last fragment to pass the depth test there (no blending, no partial
  // write mask, a shader that cannot discard, the test before shading), each triangle's passing
  // fragments are listed as they pass, and after the tile's last triangle only those still
  // visible are shaded. The colours are the same bits: a pixel's colour is its last passing
  // fragment's either way, and what the shader gets at a lane does not depend on which other
  // lanes are shaded. Counters count every passing fragment as shaded, the work the pipeline
  // stands for (W1: 574,277 passing fragments, 378,472 kept).
  constexpr bool kMayDeferShading = kSamples == 1 && !PS::kMayDiscard &&
                                    !kTakesDerivatives<PS> && !kShadesPerTriangle<PS> &&
                                    !kHasSideEffects<PS>;
  const bool deferShading = kMayDeferShading && cfg.deferShading && cfg.colorWrite &&
                            !cfg.colorMerge && (!depthRead || earlyTest);
  const bool useBounds = earlyTest && isOrderedCompare(cfg.compare);
  // The extremes of the sample positions over the tile, for the triangle's depth range.
  float offMinX = 0, offMaxX = 0, offMinY = 0, offMaxY = 0;
  for (int s = 0; s < S; ++s) {
    offMinX = std::min(offMinX, cfg.samples.offsetXPixels(s));
    offMaxX = std::max(offMaxX, cfg.samples.offsetXPixels(s));
    offMinY = std::min(offMinY, cfg.samples.offsetYPixels(s));
    offMaxY = std::max(offMaxY, cfg.samples.offsetYPixels(s));
  }
  const CoverageMask validLanes = rectMask({x0, y0, x0 + cols, y0 + rows}, tileX, tileY);
  TileDepthBounds stored;
  bool depthDirty = cfg.clearFirst && depthUsed, colorDirty = cfg.clearFirst && cfg.colorWrite;
  bool countsDirty = false;
  std::array<CoverageMask, kMaxSamples> mask;
  std::array<TileLanes<float>, kMaxSamples> z;
  ShadedColors& shaded = tile.shaded;
  TileLanes<PackedColor>& packed = tile.packed;
  glm::vec4 triangleColor{};  // kShadesPerTriangle: the one result
  // kShadesPerTriangle: the colour packed last and its packing, reused while the shader returns
  // the same bits. Such shaders return few colours (a constant, one per facing), and comparing
  // 16 bytes costs less than packColor's four clamps and conversions, once per triangle and tile.
  glm::vec4 lastColor{};
  PackedColor lastPacked = packColor(lastColor);
  auto packTriangleColor = [&](const glm::vec4& c) RAST_TILE_LAMBDA {
    if (std::memcmp(&c, &lastColor, sizeof c) != 0) {
      lastColor = c;
      lastPacked = packColor(c);
    }
    return lastPacked;
  };

  // Deferred whole-tile writes, as a GPU keeps a tile's depth as a plane until a pixel needs its
  // own value: a triangle that covers every sample of a full tile, passes the depth test on all
  // of them by the tile's bounds and writes one colour (a per-triangle shader) replaces the whole
  // tile, so its depth plane and colour are remembered instead of written to 64 lanes. The lanes
  // are written (the same depthLanes and packColor, so the same bits) only when a later triangle
  // reads or partly writes them, or when the tile is stored. Overdraw of full layers (W3) then
  // costs one coverage and bounds test per layer and tile.
  const SetupTriangle<N>* pendingDepth = nullptr;
  bool pendingColor = false;
  PackedColor pendingColorValue = 0;
  auto writePending = [&]() RAST_TILE_LAMBDA {
    if (pendingDepth)
      for (int s = 0; s < S; ++s) {
        depthLanes(*pendingDepth, x0, y0, cfg.samples.offsetXPixels(s),
                   cfg.samples.offsetYPixels(s), 0, kTileSize, tile.depth[s]);
        if (cfg.quantizeDepthLanes) cfg.quantizeDepthLanes(tile.depth[s], 0, kTileSize);
      }
    if (pendingColor)
      for (int s = 0; s < S; ++s) tile.color[s].fill(pendingColorValue);
    pendingDepth = nullptr;
    pendingColor = false;
  };
  // Whether a triangle covering every sample of the tile may be deferred: nothing of it depends
  // on a lane's stored value or differs from lane to lane. (Padding lanes of an edge tile would
  // get plane values instead of a copy of lane 0, so edge tiles are never deferred.)
  const bool mayDefer = validLanes == kFullMask && !counting && !cfg.colorMerge &&
                        (!depthRead || earlyTest) && !PS::kMayDiscard &&
                        (kShadesPerTriangle<PS> || !cfg.colorWrite) &&
                        (cfg.depthWrite || cfg.colorWrite);

  // Where the triangle's bounds meet the tile in a few pixels (small triangles), those pixels are
  // evaluated directly (coverRect) instead of the tile's 64 by the kernel, whenever a SIMD kernel
  // is chosen: the scalar reference kernel keeps the reference path for every tile, and the tests
  // compare the two. Every rectangle short of the whole tile (up to 63 pixels: fewer than the
  // tile's 64, which the kind Partial below relies on): at most eight rows of four 64-bit pairs
  // cost less than the kernel's call and per-edge preparation (against a limit of 36 pixels,
  // W4's back end 0.91x at 1 thread and 0.92x at 2, W1's 0.95x and 0.98x, W2 even).
  constexpr int kSmallRectPixels = 63;
  // Up to this many covered pixels a triangle's depth is tested pixel by pixel (fewPixels).
  constexpr uint64_t kFewPixels = 8;
  const bool testFewPixels = S == 1 && useBounds && cfg.kernel.simd != nullptr;
  static_assert(kSmallRectPixels < kTileLanes);
  const bool coverSmallRects =
      S == 1 && cfg.rasterMode == RasterMode::FixedPoint && cfg.kernel.simd != nullptr;
  // Small rectangles are rasterized, depth tested and depth written in one pass
  // (rect_early_depth.h) whenever nothing stands between coverage and the depth write: the test
  // comes before shading (or there is none), the shader cannot discard, and the format stores
  // float depths as they are (no quantising). The scalar reference kernel has no such pass.
  const bool fuseRects = coverSmallRects && cfg.rectEarlyDepth != nullptr &&
                         (!depthRead || earlyTest) && !PS::kMayDiscard && cfg.quantize == nullptr;
  const RectDraw rectDraw{cfg.format, cfg.compare, cfg.depthWrite};
  // `r`: the triangle's bounds within the tile (tileRectOf).
  auto cover = [&](const SetupTriangle<N>& t, uint32_t id, const TileRect& r, int s)
                   RAST_TILE_LAMBDA -> TileCoverageResult {
    if (cfg.rasterMode == RasterMode::Float)
      return coverTileFloat(triangles.floatEdges(id), t.bounds, tileX, tileY);
    if (coverSmallRects) {
      if (r.x0 < r.x1 && r.y0 < r.y1 && (r.x1 - r.x0) * (r.y1 - r.y0) <= kSmallRectPixels) {
        // A rectangle smaller than the tile rules out Inside (the tile within the bounds), and a
        // covered sample rules out Outside (an edge negative over the whole tile): the kind is
        // Partial, as coverTile finds. With no sample covered, the whole-tile test coverTile
        // starts with (classifyTile: one edge negative at all four corners) tells Outside from
        // Partial with an empty mask, without a second, whole-tile coverage.
        const CoverageMask m = coverRect(t.edges, r, tileX, tileY, cfg.format);
        if (m ||
            classifyTile(t.edges, t.bounds, tileX, tileY, cfg.format) != TileCoverage::Outside)
          return {m, TileCoverage::Partial};
        return {0, TileCoverage::Outside};
      }
    }
    return coverTile(cfg.kernel, t.edges, t.bounds, tileX, tileY, cfg.format,
                     cfg.samples.offsetX(s, cfg.format), cfg.samples.offsetY(s, cfg.format));
  };

  tile.deferredCount = 0;
  // The listed fragments, last first: a lane a later triangle wrote is not shaded again.
  auto shadeDeferred = [&]() RAST_TILE_LAMBDA {
    if constexpr (kMayDeferShading && kShadesWholeRows<PS>) {
      // A shader safe on any lane runs once over the rows the visible lanes touch, each lane with
      // the varyings of the triangle that owns it, instead of once over each triangle's rows (W1:
      // a tile's visible triangles cover a few pixels of two or three rows each). What the shader
      // gets at a lane is what shadePixels gives it there (interpolateRowsWhere has
      // interpolateRows' bits, and depth, facing and id are the owner's), so the colours are the
      // same bits. Lanes that no fragment owns are shaded from whatever they hold and not written.
      if (tile.deferredCount == 0) return;
      TileVaryings<N> varyings{};
      std::array<uint8_t, kTileLanes> owner{};  // per lane: its entry in tile.deferred
      static_assert(TileBuffer::kMaxDeferred <= 256);
      CoverageMask later = 0;
      for (int k = tile.deferredCount; k-- > 0 && later != validLanes;) {
        const DeferredShading& d = tile.deferred[size_t(k)];
        const CoverageMask visible = d.passed & ~later;
        later |= d.passed;
        if (!visible) continue;
        interpolateRowsWhere<N>(triangles[d.triangle], x0, y0, visible, varyings);
        for (CoverageMask m = visible; m; m &= m - 1) owner[size_t(std::countr_zero(m))] = uint8_t(k);
      }
      const RowRange rows = coveredRows(later);
      shadeWholeRows<PS, N>(
          rows, x0, y0, varyings,
          [&](int bit) RAST_TILE_LAMBDA -> const SetupTriangle<N>& {
            return triangles[tile.deferred[owner[size_t(bit)]].triangle];
          },
          shader, shaded);
      packRowColors(shaded, rows.begin, rows.end, packed);
      copyLanesWhere(later, packed, tile.color[0]);
      tile.deferredCount = 0;
    } else if constexpr (kMayDeferShading) {
      CoverageMask later = 0;
      for (int k = tile.deferredCount; k-- > 0 && later != validLanes;) {
        const DeferredShading& d = tile.deferred[size_t(k)];
        const CoverageMask visible = d.passed & ~later;
        later |= d.passed;
        if (!visible) continue;
        const SetupTriangle<N>& t = triangles[d.triangle];
        shadePixels(t, x0, y0, visible, shader, shaded, stats);
        if constexpr (kShadesWholeRows<PS>) {
          const RowRange rows = coveredRows(visible);
          packRowColors(shaded, rows.begin, rows.end, packed);
        } else {
          packLanes(shaded, visible, packed);
        }
        copyLanesWhere(visible, packed, tile.color[0]);
      }
      tile.deferredCount = 0;
    }
  };

  // Bins list triangles in submission order, scattered in memory (W1's 9.5 MB of them come from
  // L3 or memory): each entry's triangle is fetched kAhead entries before it is worked on, and the
  // tile's first kAhead before its first. Two ahead, without the first ones, left the load of
  // each triangle's bounds 6 % of W1's frame in `perf`; eight ahead took the back end 0.79-0.83x
  // on W4 and 0.87-0.89x on W1 (12 and 16 measured the same as 8; the next tile's first entries
  // fetched from the tile before, no better).
  constexpr size_t kAhead = 8;
  auto prefetchEntry = [&](size_t e) RAST_TILE_LAMBDA {
    const char* p = reinterpret_cast<const char*>(&triangles[bin[e] & ~kWholeTileBit]);
    for (size_t line = 0; line < sizeof(SetupTriangle<N>); line += 64) __builtin_prefetch(p + line);
  };
  for (size_t e = 0; e < std::min(kAhead, bin.size()); ++e) prefetchEntry(e);
  for (size_t b = 0; b < bin.size(); ++b) {
    const uint32_t id = bin[b] & ~kWholeTileBit;
    const SetupTriangle<N>& t = triangles[id];
    if (b + kAhead < bin.size()) prefetchEntry(b + kAhead);
    CoverageMask anySample = 0;
    uint64_t covered = 0;
    float triMin = 0, triMax = 0;
    // The rows the depth test reads. Plain ints, not a structured binding: lambdas use them,
    // and clang (the fuzzer build) does not let a lambda capture a binding.
    int rowBegin = 0, rowEnd = 0;
    bool depthWritten = false;  // by the fused kernel, before shading
    auto depthTest = [&]() RAST_TILE_LAMBDA {
      uint64_t passed = 0;
      anySample = 0;
      for (int s = 0; s < S; ++s) {
        mask[s] = depthTestInline(cfg.compare, z[s], tile.depth[s], mask[s], rowBegin, rowEnd);
        anySample |= mask[s];
        passed += uint64_t(popcount64(mask[s]));
      }
      return passed;
    };

    // Small rectangles: where the tile is not inside the triangle's bounds, the bounds meet it
    // in fewer than its 64 pixels.
    const bool smallRect = !(t.bounds.x0 <= x0 && t.bounds.y0 <= y0 &&
                             t.bounds.x1 >= x0 + kTileSize && t.bounds.y1 >= y0 + kTileSize);
    if (fuseRects && smallRect && !(bin[b] & kWholeTileBit)) {
      // Coverage, depth test and depth write in one pass over the rectangle's rows
      // (rect_early_depth.h). The depth lanes must hold the tile's values first.
      writePending();
      const RectEarlyDepth r = cfg.rectEarlyDepth(t, tileX, tileY, rectDraw, tile.depth[0].data());
      // The kinds coverRect's path counts: a rectangle short of the tile is Partial, or Outside
      // when classifyTile says so of an empty one.
      if (!r.covered) {
        if (classifyTile(t.edges, t.bounds, tileX, tileY, cfg.format) == TileCoverage::Outside)
          ++stats.tilesTriviallyRejected;
        else
          ++stats.tilesPartial;
        continue;
      }
      ++stats.tilesPartial;
      covered = uint64_t(popcount64(r.covered));
      stats.samplesCovered += covered;
      if (depthRead) {
        const uint64_t passes = uint64_t(popcount64(r.passed));
        stats.depthTestsPassed += passes;
        stats.depthTestsFailed += covered - passes;
      }
      if (!r.passed) continue;
      mask[0] = anySample = r.passed;
      if (cfg.depthWrite) {
        // The stored bounds are not widened (that would cost every entry its depth range): the
        // next entry that reads them recomputes them.
        depthWritten = depthDirty = true;
        stored.valid = false;
      }
    } else {
      if (bin[b] & kWholeTileBit) {
        // Binning's corner test, with the MSAA reach, found every sample inside: what coverTile
        // would return for each sample.
        ++stats.tilesTriviallyAccepted;
        for (int s = 0; s < S; ++s) mask[s] = kFullMask;
        anySample = kFullMask;
        covered = uint64_t(S) * kTileLanes;
      } else {
        for (int s = 0; s < S; ++s) {
          const TileCoverageResult c = cover(t, id, tileRectOf(t.bounds, tileX, tileY), s);
          if (s == 0) {
            // Whole-tile outcomes are counted for sample 0, the only one without MSAA.
            if (c.kind == TileCoverage::Outside) ++stats.tilesTriviallyRejected;
            else if (c.kind == TileCoverage::Inside) ++stats.tilesTriviallyAccepted;
            else ++stats.tilesPartial;
          }
          mask[s] = c.mask;
          anySample |= c.mask;
          covered += uint64_t(popcount64(c.mask));
        }
      }
      if (!anySample) continue;
      stats.samplesCovered += covered;

      // A triangle that covers a few pixels of the tile (small triangles, and the edges and corners
      // of larger ones; each of W2 tiny-1's covers one) has its depth computed and tested at those
      // pixels alone, instead of at the tile's corners against the tile's stored bounds (which cost
      // a pass over the 64 stored lanes the first time in a tile) and then along rows of eight
      // lanes. The same interpolateDepth, quantising and compare at each covered pixel as on the
      // lanes (depthLanes and depthTestLanes are written to agree with them bit for bit), so the
      // same depths, passes and counts; triMin and triMax become the range of the passing depths,
      // which is all the stored bounds need below. As with coverSmallRects, the scalar reference
      // kernel keeps the lane path, and the tests compare the two.
      const bool fewPixels = testFewPixels && covered <= kFewPixels;
      if (fewPixels) {
        writePending();
        const float dx0 = float(x0 - t.bounds.x0) + cfg.samples.offsetXPixels(0);
        const float dy0 = float(y0 - t.bounds.y0) + cfg.samples.offsetYPixels(0);
        const FewPixelsPassed r = depthTestFewPixelsInline(cfg.compare, t, mask[0], dx0, dy0,
                                                           cfg.quantize, tile.depth[0], z[0]);
        const uint64_t passes = uint64_t(popcount64(r.passed));
        stats.depthTestsPassed += passes;
        stats.depthTestsFailed += covered - passes;
        if (!r.passed) continue;
        mask[0] = anySample = r.passed;
        triMin = r.lo;
        triMax = r.hi;
      } else if (useBounds) {
        const float ax = float(x0 - t.bounds.x0), ay = float(y0 - t.bounds.y0);
        const float bx = ax + float(cols - 1), by = ay + float(rows - 1);
        const PlaneEquation& plane = t.depth;
        if (std::fabs(plane.at0) < 0x1p100f && std::fabs(plane.ddx) < 0x1p100f &&
            std::fabs(plane.ddy) < 0x1p100f) {
          // The plane's float value is monotonic in dx and in dy (TileDepthBounds), and with these
          // magnitudes (|dx|, |dy| < 2^15) no step of it overflows: its least value over the tile
          // is at the corner its slopes point away from and its greatest at the opposite one, the
          // min and max of the four corners in two evaluations.
          const float left = ax + offMinX, right = bx + offMaxX, top = ay + offMinY,
                      bottom = by + offMaxY;
          const bool growsRight = plane.ddx >= 0, growsDown = plane.ddy >= 0;
          triMin = interpolateDepth(t, growsRight ? left : right, growsDown ? top : bottom);
          triMax = interpolateDepth(t, growsRight ? right : left, growsDown ? bottom : top);
        } else {
          const float corners[4] = {interpolateDepth(t, ax + offMinX, ay + offMinY),
                                    interpolateDepth(t, bx + offMaxX, ay + offMinY),
                                    interpolateDepth(t, ax + offMinX, by + offMaxY),
                                    interpolateDepth(t, bx + offMaxX, by + offMaxY)};
          triMin = std::min({corners[0], corners[1], corners[2], corners[3]});
          triMax = std::max({corners[0], corners[1], corners[2], corners[3]});
        }
        // Quantising is monotonic, so the quantised range bounds the quantised lanes.
        if (cfg.quantize) {
          triMin = cfg.quantize(triMin);
          triMax = cfg.quantize(triMax);
        }
        if (!stored.valid) {
          writePending();
          stored = tileDepthBounds(tile.depth, S);
        }
        if (allFail(cfg.compare, triMin, triMax, stored)) {
          stats.depthTestsFailed += covered;
          continue;
        }
      }

      bool coversAll = mayDefer && !fewPixels;
      for (int s = 0; s < S && coversAll; ++s) coversAll = mask[s] == kFullMask;
      if (coversAll &&
          (!depthRead || (useBounds && allPass(cfg.compare, triMin, triMax, stored)))) {
        if (depthRead) stats.depthTestsPassed += covered;
        if constexpr (kShadesPerTriangle<PS>) {
          if (cfg.colorWrite) {
            // Run once, at the tile's first pixel, as the per-triangle path below does.
            pendingColorValue =
                packTriangleColor(shadeOncePerTriangle(t, x0, y0, 0, shader).color);
            pendingColor = colorDirty = true;
            stats.pixelShaderInvocations += kTileLanes;
          }
        }
        if (cfg.depthWrite) {
          pendingDepth = &t;
          depthDirty = true;
          if (stored.valid) {
            if (triMin == triMin && triMax == triMax) stored = {triMin, triMax, false, true};
            else stored.valid = false;
          }
        }
        stats.fragmentsWritten += kTileLanes;
        continue;
      }
      writePending();

      // Rows the triangle covers here: small triangles touch few, and only those are evaluated.
      const RowRange touched = coveredRows(anySample);
      rowBegin = touched.begin;
      rowEnd = touched.end;
      if (depthUsed && !fewPixels)
        for (int s = 0; s < S; ++s) {
          depthLanes(t, x0, y0, cfg.samples.offsetXPixels(s), cfg.samples.offsetYPixels(s),
                     rowBegin, rowEnd, z[s]);
          if (cfg.quantizeDepthLanes) cfg.quantizeDepthLanes(z[s], rowBegin, rowEnd);
        }

      const bool earlyLaneTest = earlyTest && !fewPixels;  // (fewPixels tested above)
      if (earlyLaneTest && !(useBounds && allPass(cfg.compare, triMin, triMax, stored))) {
        const uint64_t passed = depthTest();
        stats.depthTestsPassed += passed;
        stats.depthTestsFailed += covered - passed;
        if (!anySample) continue;
      } else if (earlyLaneTest) {
        stats.depthTestsPassed += covered;
      }

    }

    if (shade && deferShading) {
      if (tile.deferredCount == TileBuffer::kMaxDeferred) shadeDeferred();
      tile.deferred[size_t(tile.deferredCount++)] = {id, anySample};
      stats.pixelShaderInvocations += uint64_t(popcount64(anySample));
      colorDirty = true;
    } else if (shade) {
      CoverageMask kept = anySample;
      if constexpr (kShadesPerTriangle<PS>) {
        const PixelResult result =
            shadeOncePerTriangle(t, x0, y0, std::countr_zero(anySample), shader);
        stats.pixelShaderInvocations += uint64_t(popcount64(anySample));
        if constexpr (PS::kMayDiscard) {
          if (result.discard) {
            stats.fragmentsDiscarded += uint64_t(popcount64(anySample));
            kept = 0;
          }
        }
        triangleColor = result.color;
      } else {
        kept = shadePixels(t, x0, y0, anySample, shader, shaded, stats);
        stats.pixelShaderInvocations += uint64_t(popcount64(anySample));
        stats.fragmentsDiscarded += uint64_t(popcount64(anySample & ~kept));
      }
      if (kept != anySample) {
        anySample = kept;
        for (int s = 0; s < S; ++s) mask[s] &= kept;
      }
      if (!kept) continue;
    }
    if (depthRead && !earlyTest) {
      uint64_t before = 0;
      for (int s = 0; s < S; ++s) before += uint64_t(popcount64(mask[s]));
      const uint64_t passed = depthTest();
      stats.depthTestsPassed += passed;
      stats.depthTestsFailed += before - passed;
      if (!anySample) continue;
    }

    if (cfg.depthWrite && !depthWritten) {
      for (int s = 0; s < S; ++s) copyLanesWhere(mask[s], z[s], tile.depth[s]);
      depthDirty = true;
      if (stored.valid) {
        bool overwroteAll = true;
        for (int s = 0; s < S; ++s) overwroteAll &= (mask[s] & validLanes) == validLanes;
        if (!(triMin == triMin && triMax == triMax)) {
          stored.valid = false;
        } else if (overwroteAll) {
          stored = {triMin, triMax, false, true};  // every stored value is now the triangle's
        } else {
          stored.min = std::min(stored.min, triMin);
          stored.max = std::max(stored.max, triMax);
        }
      }
    }
    if (cfg.colorWrite && !deferShading) {
      if (cfg.colorMerge) {
        for (int s = 0; s < S; ++s) {
          for (CoverageMask m = mask[s]; m; m &= m - 1) {
            const int i = std::countr_zero(m);
            const glm::vec4 src = kShadesPerTriangle<PS> ? triangleColor : shaded.at(i);
            tile.color[s][i] = blendAndPack(src, tile.color[s][i], cfg.blend, cfg.colorWriteMask);
          }
          if (cfg.blend.enable) stats.samplesBlended += uint64_t(popcount64(mask[s]));
        }
      } else if constexpr (kShadesPerTriangle<PS>) {
        const PackedColor c = packTriangleColor(triangleColor);
        for (int s = 0; s < S; ++s) fillLanesWhere(mask[s], c, tile.color[s]);
      } else if constexpr (kShadesWholeRows<PS>) {
        const RowRange rows = coveredRows(anySample);
        packRowColors(shaded, rows.begin, rows.end, packed);
        for (int s = 0; s < S; ++s) copyLanesWhere(mask[s], packed, tile.color[s]);
      } else {
        packLanes(shaded, anySample, packed);
        for (int s = 0; s < S; ++s) copyLanesWhere(mask[s], packed, tile.color[s]);
      }
      colorDirty = true;
    }
    if (counting) {
      for (CoverageMask m = anySample; m; m &= m - 1) ++tile.counts[std::countr_zero(m)];
      countsDirty = true;
    }
    stats.fragmentsWritten += uint64_t(popcount64(anySample));
  }

  shadeDeferred();
  writePending();
  if (depthDirty)
    for (int s = 0; s < S; ++s) store(target.depth + s * planeSize, tile.depth[s]);
  if (colorDirty)
    for (int s = 0; s < S; ++s) store(target.color + s * planeSize, tile.color[s]);
  if (countsDirty) store(target.counts, tile.counts);
}

// `value` in [first, last), with non-temporal stores where 16-byte aligned: nothing in this draw
// reads these pixels again, so their lines are written without first being read for ownership
// (W1 at 2 threads: ordinary stores made the frame as slow as clear() first, 14.70 ms both).
template <class T>
RAST_TILE_INLINE void streamFill(T* first, T* last, T value) {
  static_assert(sizeof(T) == 4);
  while (first != last && reinterpret_cast<uintptr_t>(first) % 16 != 0) *first++ = value;
  const __m128i v = _mm_set1_epi32(std::bit_cast<int32_t>(value));
  for (; last - first >= 4; first += 4) _mm_stream_si128(reinterpret_cast<__m128i*>(first), v);
  while (first != last) *first++ = value;
}

// The load op's values in `count` tiles from (tileX, tileY) along a tile row, every sample plane
// of colour and of depth as asked.
RAST_TILE_INLINE void fillClearRun(const BackEndConfig& cfg, int tileX, int count, int tileY,
                                   bool color, bool depth) {
  const int x0 = tileX * kTileSize, x1 = std::min(cfg.width, (tileX + count) * kTileSize);
  const int y0 = tileY * kTileSize, y1 = std::min(cfg.height, y0 + kTileSize);
  const size_t planeSize = size_t(cfg.width) * size_t(cfg.height);
  for (int s = 0; s < cfg.samples.count; ++s)
    for (int y = y0; y < y1; ++y) {
      const size_t row = s * planeSize + size_t(y) * size_t(cfg.width);
      if (depth)
        streamFill(cfg.target.depth + row + x0, cfg.target.depth + row + x1, cfg.clearDepth);
      if (color)
        streamFill(cfg.target.color + row + x0, cfg.target.color + row + x1, cfg.clearColor);
    }
}

// The framebuffer rows a tile's load will read. Its rows lie a framebuffer width apart, a stride
// the hardware prefetcher does not follow from one tile to the next, so the back end asks for the
// next tile's while it works on this one.
RAST_TILE_INLINE void prefetchTileRows(const BackEndConfig& cfg, int tileX, int tileY) {
  const int x0 = tileX * kTileSize, y0 = tileY * kTileSize;
  const int rows = std::min(kTileSize, cfg.height - y0);
  const size_t planeSize = size_t(cfg.width) * size_t(cfg.height);
  for (int s = 0; s < cfg.samples.count; ++s)
    for (int ly = 0; ly < rows; ++ly) {
      const size_t offset = s * planeSize + size_t(y0 + ly) * size_t(cfg.width) + size_t(x0);
      if (cfg.depthUsed()) __builtin_prefetch(cfg.target.depth + offset);
      if (cfg.colorWrite) __builtin_prefetch(cfg.target.color + offset);
    }
}

// Tiles [begin, end) in order, for the baseline x86-64 target and for AVX2 (with BMI, LZCNT and
// POPCNT: the mask arithmetic gets its instructions). The two are the same source with every
// helper inlined, so the same operations in the same order: -ffp-contract=off keeps FMA out of
// the AVX2 one, and every float operation here is IEEE-exact on both, so their bits are equal
// (tests/tile_shortcuts_test.cpp compares them).
template <PixelShader PS, int N>
RAST_TILE_INLINE void rasterizeTileRange(int begin, int end, const TileBins& bins,
                                         const SetupTriangles<N>& triangles, const PS& shader,
                                         const BackEndConfig& cfg, TileBuffer& buffer,
                                         PipelineStatistics& stats) {
  const int tilesX = bins.tilesX();
  // The load op's values, written a framebuffer row at a time along runs of tiles: long runs of
  // stores, where tile by tile they were 32-byte pieces of rows a framebuffer width apart (W1 at
  // 2 threads: the frame 5 % slower than clear() first). First the planes the tile loop does not
  // keep (colour with colour writes off, depth when unused), over the whole range.
  const bool keptColor = cfg.colorWrite, keptDepth = cfg.depthUsed();
  if (cfg.clearFirst && !(keptColor && keptDepth))
    for (int first = begin; first != end;) {
      const int last = std::min(end, (first / tilesX + 1) * tilesX);
      fillClearRun(cfg, first % tilesX, last - first, first / tilesX, !keptColor, !keptDepth);
      first = last;
    }
  for (int tile = begin; tile != end; ++tile) {
    if (cfg.clearFirst && bins.empty(tile)) {
      // Then the kept planes of each run of untouched tiles along a tile row.
      int runEnd = tile + 1;
      while (runEnd != end && runEnd % tilesX != 0 && bins.empty(runEnd)) ++runEnd;
      fillClearRun(cfg, tile % tilesX, runEnd - tile, tile / tilesX, keptColor, keptDepth);
      tile = runEnd - 1;
      continue;
    }
    const int next = tile + 1;
    if (next < bins.tileCount() && !bins.empty(next))
      prefetchTileRows(cfg, next % bins.tilesX(), next / bins.tilesX());
    const int tileX = tile % bins.tilesX(), tileY = tile / bins.tilesX();
    const std::span<const uint32_t> bin = bins.entries(tile, buffer.mergedEntries);
    if (cfg.samples.count == 1)
      rasterizeTile<PS, N, 1>(tileX, tileY, bin, triangles, shader, cfg, buffer, stats);
    else
      rasterizeTile<PS, N, 0>(tileX, tileY, bin, triangles, shader, cfg, buffer, stats);
  }
  // Non-temporal stores are weakly ordered: drained before the task ends and another thread may
  // read the framebuffer.
  if (cfg.clearFirst) _mm_sfence();
}

template <PixelShader PS, int N>
void rasterizeTiles(int begin, int end, const TileBins& bins, const SetupTriangles<N>& triangles,
                    const PS& shader, const BackEndConfig& cfg, TileBuffer& buffer,
                    PipelineStatistics& stats) {
  rasterizeTileRange(begin, end, bins, triangles, shader, cfg, buffer, stats);
}

template <PixelShader PS, int N>
[[gnu::target("avx2,bmi,bmi2,lzcnt,popcnt")]] void rasterizeTilesAvx2(
    int begin, int end, const TileBins& bins, const SetupTriangles<N>& triangles,
    const PS& shader, const BackEndConfig& cfg, TileBuffer& buffer, PipelineStatistics& stats) {
  rasterizeTileRange(begin, end, bins, triangles, shader, cfg, buffer, stats);
}

inline bool cpuHasAvx2BackEnd() {
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") &&
         __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt");
}

// Runs every tile. Tiles run in parallel: each pixel belongs to one tile, and one task owns a
// tile, so no two tasks touch the same pixel, and within a tile triangles merge in submission
// order; statistics are sums, the same in any order.
template <PixelShader PS, int N = PS::kVaryings>
void runBackEnd(Framebuffer& fb, const PipelineState& state, const TileBins& bins,
                const SetupTriangles<N>& triangles, const PS& shader,
                const ExecutionOptions& exec, PipelineStatistics& stats) {
  BackEndConfig cfg;
  cfg.format = state.format;
  cfg.kernel = exec.coverage;
  cfg.rectEarlyDepth = rectEarlyDepthFor(exec.coverage);
  cfg.samples = SamplePattern::forCount(fb.samples());
  cfg.compare = state.depth.compare;
  cfg.depthWrite = state.depth.write;
  cfg.colorWrite = state.colorWrite;
  cfg.earlyDepth = state.depth.early;
  cfg.blend = state.blend;
  cfg.colorWriteMask = state.colorWriteMask;
  cfg.colorMerge = state.blend.enable || state.colorWriteMask != kWriteAll;
  cfg.rasterMode = state.rasterMode;
  cfg.deferShading = exec.deferShading;
  switch (state.depth.format) {
    case DepthFormat::Float32: break;
    case DepthFormat::Unorm24:
      cfg.quantizeDepthLanes = &quantizeLanes<DepthFormat::Unorm24>;
      cfg.quantize = &quantizeDepth<DepthFormat::Unorm24>;
      break;
    case DepthFormat::Unorm16:
      cfg.quantizeDepthLanes = &quantizeLanes<DepthFormat::Unorm16>;
      cfg.quantize = &quantizeDepth<DepthFormat::Unorm16>;
      break;
  }
  if (state.clear) {
    cfg.clearFirst = true;
    cfg.clearColor = packColor(state.clear->color);
    cfg.clearDepth = state.clear->depth;
  }
  cfg.target = {fb.colorPlane().data(), fb.depthPlane().data(),
                fb.hasCounts() ? fb.countPlane().data() : nullptr};
  cfg.width = fb.width();
  cfg.height = fb.height();

  tbb::combinable<PipelineStatistics> perTask;
  // One per thread, not per task: a TileBuffer is 6 KB that a task would zero for a few tiles.
  tbb::enumerable_thread_specific<TileBuffer> buffers;
  const bool avx2 = exec.backEnd == BackEndTarget::Auto && cpuHasAvx2BackEnd();
  tbb::parallel_for(tbb::blocked_range<int>(0, bins.tileCount(), 8),
                    [&](const tbb::blocked_range<int>& tiles) {
    PipelineStatistics& local = perTask.local();
    TileBuffer& buffer = buffers.local();
    if (avx2)
      rasterizeTilesAvx2<PS, N>(tiles.begin(), tiles.end(), bins, triangles, shader, cfg, buffer,
                                local);
    else
      rasterizeTiles<PS, N>(tiles.begin(), tiles.end(), bins, triangles, shader, cfg, buffer,
                            local);
  });
  perTask.combine_each([&](const PipelineStatistics& s) { stats += s; });
}

}  // namespace rast
