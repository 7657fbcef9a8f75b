// Per-stage microbenchmarks: vertex, clip, setup, bin, raster (per coverage kernel and
// precision), interpolate, pixel and merge, each reporting items per second on one thread.
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include <glm/vec2.hpp>

#include <tbb/task_arena.h>

#include "pipeline/draw.h"
#include "pipeline/rect_early_depth.h"
#include "rasterizer/rect_coverage.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/lambert.h"
#include "shaders_cpp/transform.h"

namespace rast {
namespace {

const Mesh& bunny() {
  static const Mesh mesh = [] {
    Mesh m;
    if (!loadObj(std::string(RASTER_SHARED_MESHES) + "/bunny.obj", m)) m = embeddedBunny();
    return m;
  }();
  return mesh;
}

// Random triangles of about `area` pixels inside a 1920x1080 screen, as shaded vertices in
// window space (w = 1), three per triangle.
std::vector<ShadedVertex<3>> randomTriangles(size_t count, double area, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> x(0, 1920), y(0, 1080), unit(0, 1);
  const float side = float(std::sqrt(2.0 * area));
  std::vector<ShadedVertex<3>> v;
  for (size_t i = 0; i < count; ++i) {
    const float cx = x(rng), cy = y(rng);
    for (int k = 0; k < 3; ++k)
      v.push_back({glm::vec4(cx + side * (unit(rng) - 0.5f), cy + side * (unit(rng) - 0.5f),
                             unit(rng), 1.0f),
                   {unit(rng), unit(rng), unit(rng)}});
  }
  return v;
}

SetupContext windowContext(FixedPointFormat format) {
  PipelineState state;
  state.viewport = {0, 0, 1920, 1080};
  state.positionSpace = PositionSpace::Window;
  state.format = format;
  return {ScreenMapping::forState(state), format, PixelRect{0, 0, 1920, 1080}, CullMode::None,
          FrontFace::CounterClockwise};
}

std::vector<SetupTriangle<3>> setUp(const std::vector<ShadedVertex<3>>& v, FixedPointFormat f) {
  const SetupContext ctx = windowContext(f);
  std::vector<SetupTriangle<3>> out;
  PipelineStatistics stats;
  SetupTriangle<3> t;
  FloatEdges unused;
  for (size_t i = 0; i + 2 < v.size(); i += 3)
    if (setupTriangle<3, ShadedVertex<3>>({&v[i], &v[i + 1], &v[i + 2]}, ctx, uint32_t(i / 3), t, unused, stats))
      out.push_back(t);
  return out;
}

void BM_VertexWorldNormal(benchmark::State& state) {
  const Mesh& mesh = bunny();
  const WorldNormalVertexShader vs{glm::mat4(1.0f), frameMesh(mesh).viewProjection(16.0f / 9)};
  tbb::task_arena one(1);
  for (auto _ : state) {
    TransformedVertices<6> out;
    PipelineStatistics stats;
    one.execute([&] {
      if (!runVertexStage<WorldNormalVertexShader, 6>(vs, mesh.vertices, mesh.indices, out, stats))
        state.SkipWithError("index out of range");
    });
    benchmark::DoNotOptimize(out.vertices.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(mesh.indices.size()));
}
BENCHMARK(BM_VertexWorldNormal)->Unit(benchmark::kMicrosecond);

// Triangles crossing the near plane (one vertex behind the eye): the full clipping path.
void BM_ClipNearPlane(benchmark::State& state) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<ShadedVertex<3>> v;
  for (int i = 0; i < 3000; ++i) {
    v.push_back({glm::vec4(u(rng), u(rng), 0.5f, 1.0f), {1, 0, 0}});
    v.push_back({glm::vec4(u(rng), u(rng), 0.5f, 1.0f), {0, 1, 0}});
    v.push_back({glm::vec4(u(rng), u(rng), -2.0f, 1.0f), {0, 0, 1}});
  }
  PipelineState ps;
  ps.viewport = {0, 0, 1920, 1080};
  const ScreenMapping m = ScreenMapping::forState(ps);
  const ClipPlanes planes = ClipPlanes::forState(ps, m);
  ClipPolygon<3> poly;
  for (auto _ : state) {
    for (size_t i = 0; i < v.size(); i += 3) {
      clipTriangle<3>({&v[i], &v[i + 1], &v[i + 2]}, planes, 0x7F, poly);
      benchmark::DoNotOptimize(poly.count);
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.size() / 3));
}
BENCHMARK(BM_ClipNearPlane)->Unit(benchmark::kMicrosecond);

// Clip codes of 100,000 vertices spread around the view volume (a quarter outside it), in
// 24.4 and 16.8 (their guard bands differ): 0 is the plane-by-plane reference (outsideMask), 1 the
// block evaluation's baseline build, 2 its AVX2 build and 3 its AVX-512 build
// (pipeline/clip_codes.h).
void BM_ClipCodes(benchmark::State& state) {
  const int method = int(state.range(0));
  const detail::ClipCodeIsa isa = method <= 1   ? detail::ClipCodeIsa::Baseline
                                  : method == 2 ? detail::ClipCodeIsa::Avx2
                                                : detail::ClipCodeIsa::Avx512;
  if (isa > detail::bestClipCodeIsa()) {
    state.SkipWithError("this build of the plane tests does not run on this machine");
    return;
  }
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(-1.25f, 1.25f), w(0.5f, 20.0f);
  std::vector<ShadedVertex<0>> v;
  for (int i = 0; i < 100000; ++i) {
    const float wi = w(rng);
    v.push_back({glm::vec4(u(rng) * wi, u(rng) * wi, u(rng) * wi, wi), {}});
  }
  PipelineState ps;
  ps.viewport = {0, 0, 1920, 1080};
  ps.format = FixedPointFormat::withFractionBits(int(state.range(1)));
  const ClipPlanes planes = ClipPlanes::forState(ps, ScreenMapping::forState(ps));
  std::vector<AxisPlane> axis;
  if (!axisPlanes(planes, axis)) {
    state.SkipWithError("planes not in two-term form");
    return;
  }
  std::vector<VertexClipCodes> codes(v.size());
  for (auto _ : state) {
    if (method == 0) {
      for (size_t i = 0; i < v.size(); ++i)
        codes[i] = referenceClipCodes(glm::dvec4(v[i].position), planes);
    } else {
      for (size_t i = 0; i < v.size(); i += detail::kClipCodeBlock)
        detail::clipCodesBlock(&v[i], int(std::min<size_t>(detail::kClipCodeBlock, v.size() - i)),
                               axis, isa, &codes[i]);
    }
    benchmark::DoNotOptimize(codes.data());
    benchmark::ClobberMemory();
  }
  static const char* const kNames[] = {"reference", "blocks baseline", "blocks AVX2",
                                       "blocks AVX-512"};
  state.SetLabel(std::string(kNames[method]) + " " + ps.format.name());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.size()));
}
BENCHMARK(BM_ClipCodes)->ArgsProduct({{0, 1, 2, 3}, {4, 8}})->Unit(benchmark::kMicrosecond);

void BM_SetupTriangle(benchmark::State& state) {
  const FixedPointFormat f = FixedPointFormat::withFractionBits(int(state.range(0)));
  const std::vector<ShadedVertex<3>> v = randomTriangles(10000, 50, 1);
  const SetupContext ctx = windowContext(f);
  SetupTriangle<3> t;
  FloatEdges unused;
  PipelineStatistics stats;
  for (auto _ : state) {
    for (size_t i = 0; i < v.size(); i += 3) {
      benchmark::DoNotOptimize(setupTriangle<3, ShadedVertex<3>>({&v[i], &v[i + 1], &v[i + 2]}, ctx, 0, t, unused, stats));
    }
  }
  state.SetLabel(f.name());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.size() / 3));
}
BENCHMARK(BM_SetupTriangle)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);

// The same triangles through SetupBatch (pipeline/setup_batch.h), which the front end uses for
// unclipped triangles in fixed-point mode: arg 1 picks the build of its loops (0 baseline,
// 1 AVX2, 2 AVX-512). Compare with BM_SetupTriangle at the same precision.
void BM_SetupBatch(benchmark::State& state) {
  const FixedPointFormat f = FixedPointFormat::withFractionBits(int(state.range(0)));
  const auto isa = detail::SetupIsa(state.range(1));
  if (isa > detail::bestSetupIsa()) {
    state.SkipWithError("not supported by this CPU");
    return;
  }
  const std::vector<ShadedVertex<3>> v = randomTriangles(10000, 50, 1);
  const SetupContext ctx = windowContext(f);
  ScratchVector<SetupTriangle<3>> out;
  out.reserve(v.size() / 3);
  PipelineStatistics stats;
  for (auto _ : state) {
    out.clear();
    SetupBatch<3> batch(ctx, isa);
    for (size_t i = 0; i < v.size(); i += 3) {
      batch.add({&v[i], &v[i + 1], &v[i + 2]}, 0);
      if (batch.full()) batch.flush(out, stats);
    }
    batch.flush(out, stats);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetLabel(f.name() + " " + detail::setupIsaName(isa));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.size() / 3));
}
BENCHMARK(BM_SetupBatch)->ArgsProduct({{4, 8}, {0, 1, 2}})->Unit(benchmark::kMicrosecond);

void BM_BinSmallTriangles(benchmark::State& state) {
  const std::vector<SetupTriangle<3>> tris =
      setUp(randomTriangles(100000, double(state.range(0)), 2), FixedPointFormat::d24_4());
  // One chunk per 4096 triangles, as the front end leaves them.
  std::vector<std::vector<SetupTriangle<3>>> chunks;
  for (size_t i = 0; i < tris.size(); i += 4096)
    chunks.emplace_back(tris.begin() + ptrdiff_t(i),
                        tris.begin() + ptrdiff_t(std::min(tris.size(), i + 4096)));
  tbb::task_arena one(1);
  for (auto _ : state) {
    TileBins bins(1920, 1080);
    PipelineStatistics stats;
    one.execute([&] {
      bins.build(chunks, FixedPointFormat::d24_4(), 0, &SetupTriangles<3>::id, stats);
    });
    benchmark::DoNotOptimize(bins.entryCount());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(tris.size()));
}
BENCHMARK(BM_BinSmallTriangles)->Arg(10)->Arg(1000)->Unit(benchmark::kMicrosecond);

// W3's layers: 16 full-screen quads (32 triangles), binned with both levels (first argument 0:
// coarse tiles first, 1: tile by tile) in both precisions (second: fraction bits), one thread.
// Items: (triangle, tile) pairs, counted as one-level binning makes them, so the rates compare
// directly.
void BM_BinFullScreenLayers(benchmark::State& state) {
  const BinLevels levels = state.range(0) == 0 ? BinLevels::Coarse : BinLevels::TilesOnly;
  const FixedPointFormat format = FixedPointFormat::withFractionBits(int(state.range(1)));
  std::vector<ShadedVertex<3>> v;
  for (int layer = 0; layer < 16; ++layer) {
    const float z = float(layer) / 16;
    for (glm::vec2 p : {glm::vec2(0, 0), glm::vec2(1920, 0), glm::vec2(1920, 1080),
                        glm::vec2(0, 0), glm::vec2(1920, 1080), glm::vec2(0, 1080)})
      v.push_back({glm::vec4(p, z, 1.0f), {0, 0, 0}});
  }
  const std::vector<std::vector<SetupTriangle<3>>> chunks = {setUp(v, format)};
  tbb::task_arena one(1);
  size_t entries = 0;
  for (auto _ : state) {
    TileBins bins(1920, 1080, nullptr, levels);
    PipelineStatistics stats;
    one.execute([&] { bins.build(chunks, format, 0, &SetupTriangles<3>::id, stats); });
    entries = bins.entryCount();
    benchmark::DoNotOptimize(entries);
  }
  state.SetLabel(std::string(levels == BinLevels::Coarse ? "coarse tiles first, " : "tile by tile, ") +
                 format.name());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(entries));
}
BENCHMARK(BM_BinFullScreenLayers)
    ->ArgNames({"levels", "bits"})
    ->ArgsProduct({{0, 1}, {4, 8}})
    ->Unit(benchmark::kMicrosecond);

// Partial tiles only (the per-sample work), for each kernel and precision.
void BM_RasterCoverage(benchmark::State& state, const CoverageKernel& kernel, int bits) {
  const FixedPointFormat f = FixedPointFormat::withFractionBits(bits);
  const std::vector<SetupTriangle<3>> tris = setUp(randomTriangles(20000, 200, 3), f);
  struct Job { size_t tri; int tx, ty; };
  std::vector<Job> jobs;
  for (size_t i = 0; i < tris.size(); ++i) {
    const PixelRect& b = tris[i].bounds;
    for (int ty = b.y0 >> 3; ty <= (b.y1 - 1) >> 3; ++ty)
      for (int tx = b.x0 >> 3; tx <= (b.x1 - 1) >> 3; ++tx)
        if (classifyTile(tris[i].edges, b, tx, ty, f) == TileCoverage::Partial)
          jobs.push_back({i, tx, ty});
  }
  for (auto _ : state)
    for (const Job& j : jobs)
      benchmark::DoNotOptimize(coverTile(kernel, tris[j.tri].edges, tris[j.tri].bounds, j.tx, j.ty, f).mask);
  state.SetLabel(kernel.name + " " + f.name());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(jobs.size()));
  state.counters["samples/s"] = benchmark::Counter(
      double(state.iterations()) * double(jobs.size()) * 64, benchmark::Counter::kIsRate);
}

// Small triangles (about 10 px², W1's and tiny-10's size) in the tiles their bounds meet in at
// most 36 pixels, the back end's coverRect case: each kernel's whole-tile coverage (kernel =
// nullptr: coverRect, the pixels of the rectangle alone), on the same (triangle, tile) pairs, so
// that the rates compare side by side.
void BM_RasterSmallRect(benchmark::State& state, const CoverageKernel* kernel, int bits) {
  const FixedPointFormat f = FixedPointFormat::withFractionBits(bits);
  const std::vector<SetupTriangle<3>> tris = setUp(randomTriangles(20000, 10, 5), f);
  struct Job { size_t tri; int tx, ty; TileRect rect; };
  std::vector<Job> jobs;
  for (size_t i = 0; i < tris.size(); ++i) {
    const PixelRect& b = tris[i].bounds;
    for (int ty = b.y0 >> 3; ty <= (b.y1 - 1) >> 3; ++ty)
      for (int tx = b.x0 >> 3; tx <= (b.x1 - 1) >> 3; ++tx) {
        const TileRect r = tileRectOf(b, tx, ty);
        if ((r.x1 - r.x0) * (r.y1 - r.y0) <= 36) jobs.push_back({i, tx, ty, r});
      }
  }
  for (auto _ : state)
    for (const Job& j : jobs) {
      const SetupTriangle<3>& t = tris[j.tri];
      benchmark::DoNotOptimize(kernel ? coverTile(*kernel, t.edges, t.bounds, j.tx, j.ty, f).mask
                                      : coverRect(t.edges, j.rect, j.tx, j.ty, f));
    }
  state.SetLabel((kernel ? kernel->name : std::string("rect")) + " " + f.name());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(jobs.size()));
}

// The same kind of pairs, every rectangle short of the whole tile, through the back end's fused
// raster and early depth (rect_early_depth.h) of each kernel's target: coverage, the depth test
// (less) and the depth write of each pair against one tile of depths, as W4 runs them.
void BM_RasterRectEarlyDepth(benchmark::State& state, const CoverageKernel* kernel, int bits) {
  const FixedPointFormat f = FixedPointFormat::withFractionBits(bits);
  const std::vector<SetupTriangle<3>> tris = setUp(randomTriangles(20000, 10, 5), f);
  struct Job { size_t tri; int tx, ty; };
  std::vector<Job> jobs;
  for (size_t i = 0; i < tris.size(); ++i) {
    const PixelRect& b = tris[i].bounds;
    for (int ty = b.y0 >> 3; ty <= (b.y1 - 1) >> 3; ++ty)
      for (int tx = b.x0 >> 3; tx <= (b.x1 - 1) >> 3; ++tx) {
        const TileRect r = tileRectOf(b, tx, ty);
        if ((r.x1 - r.x0) * (r.y1 - r.y0) < 64) jobs.push_back({i, tx, ty});
      }
  }
  const RectEarlyDepthFn fn = rectEarlyDepthFor(*kernel);
  const RectDraw draw{f, CompareOp::Less, true};
  std::array<float, 64> depth;
  depth.fill(1.0f);
  for (auto _ : state)
    for (const Job& j : jobs) benchmark::DoNotOptimize(fn(tris[j.tri], j.tx, j.ty, draw, depth.data()));
  state.SetLabel(kernel->name + " " + f.name());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(jobs.size()));
}

void BM_InterpolateThreeVaryings(benchmark::State& state) {
  const std::vector<SetupTriangle<3>> tris = setUp(randomTriangles(1000, 500, 4), FixedPointFormat::d24_4());
  Varyings<3> v;
  int64_t n = 0;
  for (auto _ : state) {
    for (const SetupTriangle<3>& t : tris)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          interpolateVaryings<3>(t, float(x), float(y), v);
          benchmark::DoNotOptimize(v);
        }
    n += int64_t(tris.size()) * 64;
  }
  state.SetItemsProcessed(n);
}
BENCHMARK(BM_InterpolateThreeVaryings)->Unit(benchmark::kMicrosecond);

void BM_PixelLambert(benchmark::State& state) {
  const LambertShader ps;
  Fragment<6> f;
  f.varyings = {0.3f, 0.8f, 0.5f, 1.0f, 2.0f, 3.0f};
  for (auto _ : state) {
    for (int i = 0; i < 4096; ++i) {
      f.varyings[0] = float(i) * 1e-4f;
      benchmark::DoNotOptimize(ps(f));
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * 4096);
}
BENCHMARK(BM_PixelLambert)->Unit(benchmark::kMicrosecond);

// The back end's per-tile stages alone, one full 8x8 tile per triangle on a tile buffer:
// depth at 64 lanes, the depth test, constant-colour shading (per pixel here: the pipeline itself
// shades ConstantColorShader once per triangle and tile), depth and colour writes.
void BM_MergeConstantColor(benchmark::State& state) {
  const std::vector<SetupTriangle<0>> tris = [] {
    std::vector<SetupTriangle<0>> t(256);
    for (size_t i = 0; i < t.size(); ++i) {
      t[i].bounds = {0, 0, 8, 8};
      t[i].depth = {1.0f - float(i) / 512, 0, 0};
    }
    return t;
  }();
  const ConstantColorShader ps;
  TileBuffer tile;
  TileLanes<float> z;
  ShadedColors shaded;
  TileLanes<PackedColor> packed;
  PipelineStatistics stats;
  for (auto _ : state) {
    tile.depth[0].fill(1.0f);
    for (const SetupTriangle<0>& t : tris) {
      depthLanes(t, 0, 0, 0.0f, 0.0f, 0, kTileSize, z);
      const CoverageMask pass =
          depthTestLanes<CompareOp::Less>(z, tile.depth[0], kFullMask, 0, kTileSize);
      const CoverageMask kept = shadePixels(t, 0, 0, pass, ps, shaded, stats);
      copyLanesWhere(kept, z, tile.depth[0]);
      packLanes(shaded, kept, packed);
      copyLanesWhere(kept, packed, tile.color[0]);
    }
    benchmark::DoNotOptimize(tile);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(tris.size()) * 64);
}
BENCHMARK(BM_MergeConstantColor)->Unit(benchmark::kMicrosecond);

const bool kRegistered = [] {
  for (const CoverageKernel& k : availableCoverageKernels())
    for (int bits : {4, 8})
      benchmark::RegisterBenchmark(("BM_RasterCoverage/" + k.name + "/" + std::to_string(bits)).c_str(),
                                   BM_RasterCoverage, k, bits)
          ->Unit(benchmark::kMicrosecond);
  static const std::vector<CoverageKernel> kernels = availableCoverageKernels();
  for (int bits : {4, 8}) {
    benchmark::RegisterBenchmark(("BM_RasterSmallRect/rect/" + std::to_string(bits)).c_str(),
                                 BM_RasterSmallRect, nullptr, bits)
        ->Unit(benchmark::kMicrosecond);
    for (const CoverageKernel& k : kernels)
      benchmark::RegisterBenchmark(
          ("BM_RasterSmallRect/" + k.name + "/" + std::to_string(bits)).c_str(),
          BM_RasterSmallRect, &k, bits)
          ->Unit(benchmark::kMicrosecond);
    for (const CoverageKernel& k : kernels)
      if (k.simd)
        benchmark::RegisterBenchmark(
            ("BM_RasterRectEarlyDepth/" + k.name + "/" + std::to_string(bits)).c_str(),
            BM_RasterRectEarlyDepth, &k, bits)
            ->Unit(benchmark::kMicrosecond);
  }
  return true;
}();

}  // namespace
}  // namespace rast
