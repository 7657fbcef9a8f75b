// One frame of each standard workload (workloads.h) on our pipeline at 1920x1080, in ms per frame,
// and the memory-bandwidth floor that W3 cannot beat.
#include <algorithm>
#include <cstring>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/frame_counters.h"
#include "bench/workloads.h"
#include "pipeline/instrumentation.h"

namespace rast::workloads {
namespace {

std::string bunnyPath() { return std::string(RASTER_SHARED_MESHES) + "/bunny.obj"; }

// Renders frames of `geometry` with `renderFrame` (a renderW*Frame) and reports the last frame's
// counters.
template <class Geometry, class RenderFrame>
void runFrames(benchmark::State& state, const Geometry& geometry, RenderFrame renderFrame,
               int samples = 1, BackEndTarget target = BackEndTarget::Auto) {
  Framebuffer fb(kFrameWidth, kFrameHeight, false, samples);
  PipelineStatistics frame;
  // Draws reuse their temporaries' memory from frame to frame, as an application rendering
  // frames does (scratch_memory.h).
  ScratchMemory memory;
  ExecutionOptions exec;
  exec.threads = int(state.range(1));
  exec.memory = &memory;
  exec.backEnd = target;
  // Two untimed frames first, as the peer renders one before timing: the first frame of a
  // process pays for fresh pages (several times a warm frame's cost for W2's 2M triangles), and
  // a benchmark that runs a single timed iteration would report only that.
  for (int warmUp = 0; warmUp < 2; ++warmUp) {
    frame = {};
    if (Status s = renderFrame(fb, geometry, frame, exec); !s) {
      state.SkipWithError(s.message().c_str());
      return;
    }
  }
  // Where a frame's time goes, per stage (wall-clock ms per frame, averaged over the timed
  // frames): which stage keeps a workload from scaling with threads shows here.
  StageTimings stages;
  exec.timings = &stages;
  for (auto _ : state) {
    frame = {};
    if (Status s = renderFrame(fb, geometry, frame, exec); !s) {
      state.SkipWithError(s.message().c_str());
      break;
    }
    benchmark::DoNotOptimize(fb.colorPlane().data());
    benchmark::ClobberMemory();
  }
  bench::reportFrameCounts(state, {frame.inputTriangles, frame.samplesCovered,
                                   frame.depthTestsPassed, frame.pixelShaderInvocations});
  const double msPerFrame = 1e3 / double(std::max<benchmark::IterationCount>(state.iterations(), 1));
  state.counters["vertex_ms"] = stages.vertex * msPerFrame;
  state.counters["setup_ms"] = stages.clipSetup * msPerFrame;
  state.counters["bin_ms"] = stages.bin * msPerFrame;
  state.counters["back_end_ms"] = stages.backEnd * msPerFrame;
  // The back end's work items: what its time is per (ns per entry = back_end_ms * 1e6 / entries).
  state.counters["setup_triangles"] = double(frame.setupTriangles);
  state.counters["bin_entries"] = double(frame.binEntries);
}

// W1, W3 and W4's first argument: 0 runs the back end on the best target the CPU has, 1 on the
// x86-64 baseline.
BackEndTarget targetArgument(const benchmark::State& state) {
  return state.range(0) == 1 ? BackEndTarget::Baseline : BackEndTarget::Auto;
}

void litMeshFrames(benchmark::State& state,
                   Status (*renderFrame)(Framebuffer&, const LitMeshScene&, PipelineStatistics&,
                                         const ExecutionOptions&)) {
  LitMeshScene scene;
  if (Status s = loadLitMeshScene(bunnyPath(), kFrameWidth, kFrameHeight, scene); !s) {
    state.SkipWithError(s.message().c_str());
    return;
  }
  runFrames(state, scene, renderFrame, 1, targetArgument(state));
}

void BM_FrameW1(benchmark::State& state) { litMeshFrames(state, renderW1Frame); }

void BM_FrameW2Tiny(benchmark::State& state) {
  const WindowGeometry grid =
      triangleGrid(double(state.range(0)), kFrameWidth, kFrameHeight, kTinyTriangleDepth);
  runFrames(state, grid, renderW2Frame);
}

template <LayerOrder kOrder, LayerShape kShape>
void BM_FrameW3(benchmark::State& state) {
  runFrames(state, overdrawLayers(kFrameWidth, kFrameHeight, kOrder, kShape), renderW3Frame, 1,
            targetArgument(state));
}

void BM_FrameW4(benchmark::State& state) { litMeshFrames(state, renderW4Frame); }

// Feature costs, each against its plain workload in the same run: W1 at 1, 4 and 8 samples per
// pixel (the first argument), and W3 back to front with alpha blending instead of overwriting.
void BM_FrameW1Msaa(benchmark::State& state) {
  LitMeshScene scene;
  if (Status s = loadLitMeshScene(bunnyPath(), kFrameWidth, kFrameHeight, scene); !s) {
    state.SkipWithError(s.message().c_str());
    return;
  }
  runFrames(state, scene, renderW1Frame, int(state.range(0)));
}

Status renderW3BlendedFrame(Framebuffer& fb, const WindowGeometry& layers,
                            PipelineStatistics& stats, const ExecutionOptions& exec) {
  PipelineState state = workloadState(fb.width(), fb.height(), PositionSpace::Window);
  state.blend = BlendState::alphaBlend();
  state.clear = ClearValues{kClearColor, kClearDepth};
  return drawFlatGeometry(fb, state, layers, stats, exec);
}

void BM_FrameW3BackToFrontBlended(benchmark::State& state) {
  runFrames(state, overdrawLayers(kFrameWidth, kFrameHeight, LayerOrder::BackToFront, LayerShape::Quad),
            renderW3BlendedFrame, 1, targetArgument(state));
}

// One write of W3's framebuffer bytes (RGBA8 colour and 32-bit depth): what any renderer that
// writes every pixel once must at least spend.
void BM_FrameMemsetFloor(benchmark::State& state) {
  Framebuffer fb(kFrameWidth, kFrameHeight);
  for (auto _ : state) {
    std::memset(fb.colorPlane().data(), 0x11, fb.colorPlane().size() * sizeof(PackedColor));
    std::memset(fb.depthPlane().data(), 0x22, fb.depthPlane().size() * sizeof(float));
    benchmark::DoNotOptimize(fb.colorPlane().data());
    benchmark::DoNotOptimize(fb.depthPlane().data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * kFrameWidth * kFrameHeight * 8);
}

// Every frame benchmark at 1 and 2 threads (the second argument), the peer's settings; the
// first argument 0 runs the back end on the best target the CPU has, 1 on the x86-64 baseline.
void withThreads(benchmark::internal::Benchmark* b) {
  b->ArgNames({"", "threads"});
  for (int target : {0, 1})
    for (int threads : {1, 2}) b->Args({target, threads});
}

#define FRAME_BENCHMARK(...) \
  BENCHMARK(__VA_ARGS__)->Unit(benchmark::kMillisecond)->UseRealTime()->Apply(withThreads)

FRAME_BENCHMARK(BM_FrameW1);
BENCHMARK(BM_FrameW2Tiny)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ArgNames({"area", "threads"})
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int area : kTinyTriangleAreas)
        for (int threads : {1, 2}) b->Args({area, threads});
    });
FRAME_BENCHMARK(BM_FrameW3<LayerOrder::FrontToBack, LayerShape::Quad>)->Name("BM_FrameW3FrontToBack");
FRAME_BENCHMARK(BM_FrameW3<LayerOrder::BackToFront, LayerShape::Quad>)->Name("BM_FrameW3BackToFront");
FRAME_BENCHMARK(BM_FrameW3<LayerOrder::FrontToBack, LayerShape::Tessellated>)
    ->Name("BM_FrameW3TessFrontToBack");
FRAME_BENCHMARK(BM_FrameW3<LayerOrder::BackToFront, LayerShape::Tessellated>)
    ->Name("BM_FrameW3TessBackToFront");
FRAME_BENCHMARK(BM_FrameW4);
BENCHMARK(BM_FrameW1Msaa)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ArgNames({"samples", "threads"})
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int samples : {1, 4, 8}) b->Args({samples, 1});
    });
FRAME_BENCHMARK(BM_FrameW3BackToFrontBlended);
BENCHMARK(BM_FrameMemsetFloor)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rast::workloads
