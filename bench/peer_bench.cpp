// The standard workloads (workloads.h) on the peer, Mesa llvmpipe, with 1 and 2 rasterizer
// threads: the same geometry, state and frame size as frame_bench.cpp, so names match up to the
// prefix (BM_FrameW1 vs BM_PeerW1/threads:N).
#include <cstdio>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/frame_counters.h"
#include "bench/llvmpipe_peer.h"
#include "bench/workloads.h"

namespace rast::workloads {
namespace {

using peer::LlvmpipePeer;

// The benchmark program's one peer context. It is kept between benchmarks so that each need not
// pay for llvmpipe's start-up, and replaced when another thread count is asked for (llvmpipe fixes
// its threads when the EGL display is initialised, and a process has one such display). This is
// the one piece of mutable static state, and it belongs to this benchmark program alone.
LlvmpipePeer* peerWithThreads(int threads, std::string& error) {
  static std::unique_ptr<LlvmpipePeer> current;
  if (current && current->threads() == threads) return current.get();
  current.reset();  // terminates the display before the next one initialises it
  current = LlvmpipePeer::create(threads, kFrameWidth, kFrameHeight, error);
  return current.get();
}

// Skips the benchmark, and says why on stderr too: with --benchmark_report_aggregates_only the
// message would otherwise not be seen.
void skip(benchmark::State& state, const std::string& why) {
  std::fprintf(stderr, "peer benchmark skipped: %s\n", why.c_str());
  state.SkipWithError(why.c_str());
}

// Loads the workload with `load(peer)`, counts its fragments in one frame, then times frames.
template <class Load>
void runPeerFrames(benchmark::State& state, uint64_t triangles, Load load) {
  std::string error;
  LlvmpipePeer* peer = peerWithThreads(int(state.range(0)), error);
  if (!peer) {
    skip(state, "llvmpipe peer unavailable: " + error);
    return;
  }
  load(*peer);
  const peer::FragmentCounts counts = peer->countFragments();  // also warms up
  if (std::string e = peer->takeGlError(); !e.empty()) {
    skip(state, e);
    return;
  }
  for (auto _ : state) peer->renderFrame();
  state.SetLabel(peer->renderer());
  // llvmpipe tests depth before shading these shaders, so shaded pixels are those passing depth.
  bench::reportFrameCounts(state, {triangles, counts.rasterized, counts.depthPassed,
                                   counts.depthPassed});
}

void litMeshPeerFrames(benchmark::State& state, bool colorWrite) {
  LitMeshScene scene;
  if (Status s = loadLitMeshScene(std::string(RASTER_SHARED_MESHES) + "/bunny.obj", kFrameWidth,
                                  kFrameHeight, scene);
      !s) {
    skip(state, s.message());
    return;
  }
  runPeerFrames(state, scene.mesh.triangleCount(), [&](LlvmpipePeer& peer) {
    peer.loadLitMesh(scene.mesh, scene.viewProjection, colorWrite);
  });
}

void flatPeerFrames(benchmark::State& state, const WindowGeometry& geometry) {
  const std::vector<glm::vec3> ndc =
      toNormalizedDeviceCoordinates(geometry, kFrameWidth, kFrameHeight);
  runPeerFrames(state, geometry.triangleCount(),
                [&](LlvmpipePeer& peer) { peer.loadFlatGeometry(ndc, geometry.indices); });
}

void BM_PeerW1(benchmark::State& state) { litMeshPeerFrames(state, true); }

void BM_PeerW2Tiny(benchmark::State& state) {
  flatPeerFrames(state, triangleGrid(double(state.range(1)), kFrameWidth, kFrameHeight,
                                     kTinyTriangleDepth));
}

template <LayerOrder kOrder, LayerShape kShape>
void BM_PeerW3(benchmark::State& state) {
  flatPeerFrames(state, overdrawLayers(kFrameWidth, kFrameHeight, kOrder, kShape));
}

void BM_PeerW4(benchmark::State& state) { litMeshPeerFrames(state, false); }

void threadCounts(benchmark::internal::Benchmark* b) {
  b->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_PeerW1)->Apply(threadCounts);
BENCHMARK(BM_PeerW2Tiny)
    ->ArgNames({"threads", "area"})
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int threads : {1, 2})
        for (int area : kTinyTriangleAreas) b->Args({threads, area});
    })
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PeerW3<LayerOrder::FrontToBack, LayerShape::Quad>)
    ->Name("BM_PeerW3FrontToBack")
    ->Apply(threadCounts);
BENCHMARK(BM_PeerW3<LayerOrder::BackToFront, LayerShape::Quad>)
    ->Name("BM_PeerW3BackToFront")
    ->Apply(threadCounts);
BENCHMARK(BM_PeerW3<LayerOrder::FrontToBack, LayerShape::Tessellated>)
    ->Name("BM_PeerW3TessFrontToBack")
    ->Apply(threadCounts);
BENCHMARK(BM_PeerW3<LayerOrder::BackToFront, LayerShape::Tessellated>)
    ->Name("BM_PeerW3TessBackToFront")
    ->Apply(threadCounts);
BENCHMARK(BM_PeerW4)->Apply(threadCounts);

}  // namespace
}  // namespace rast::workloads
