// Coverage kernels: the same 8x8-tile coverage computed by the scalar reference or by SIMD code
// compiled for several instruction sets (Highway), chosen at run time. Every kernel returns the
// reference's mask bit for bit (tests/coverage_kernels_test.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rasterizer/coverage.h"

namespace rast {

// The edges of one triangle over one tile, prepared for 32-bit lanes: E at the tile's first
// sample and its steps per pixel. The first `count` are edges that cross the tile and whose
// values over it fit in int32 (see coverTile); the rest are 0, an edge every sample passes.
struct TileEdgeSteps {
  std::array<int32_t, 3> e0;
  std::array<int32_t, 3> dx;
  std::array<int32_t, 3> dy;
  int count = 0;
};

using CoverageKernelFn = CoverageMask (*)(const TileEdgeSteps&);

struct CoverageKernel {
  std::string name;  // "scalar" (int64 reference), "HWY_SCALAR", "SSSE3", "SSE4", "AVX2", "AVX3"
  CoverageKernelFn simd = nullptr;  // null: the scalar int64 reference (coverageScalar)
  int64_t target = 0;  // Highway's target bit, for kernels compiled with this one (0: scalar)
};

// Where Highway target `target` (a bit of hwy::SupportedAndGeneratedTargets) sits in a dispatch
// table (HWY_DISPATCH_TABLE), so that other kernels can be taken for the same target.
size_t highwayTableIndex(int64_t target);

// The scalar reference first, then every SIMD target compiled in and supported by this CPU, best
// last.
std::vector<CoverageKernel> availableCoverageKernels();
// The best available kernel (the last of the list).
CoverageKernel bestCoverageKernel();
// The kernel of that name, case-insensitive ("auto": the best); false if not available here.
bool findCoverageKernel(std::string_view name, CoverageKernel& out);

struct TileCoverageResult {
  CoverageMask mask;
  TileCoverage kind;  // Outside or Inside: decided from the tile's corners, no per-sample work
};

// Coverage of one tile with the given kernel, and whether whole-tile tests decided it. The mask
// equals coverageScalar's (with the same sample offset) for every kernel; the kind equals
// classifyTile's when the offset is 0.
TileCoverageResult coverTile(const CoverageKernel& kernel,
                             const std::array<EdgeFunction, 3>& edges, const PixelRect& bounds,
                             int tileX, int tileY, FixedPointFormat format, int32_t offsetX = 0,
                             int32_t offsetY = 0);

}  // namespace rast
