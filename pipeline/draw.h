// A draw call, and the pipeline in order: the table of contents of the whole renderer.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <tbb/task_arena.h>

#include "pipeline/bin.h"
#include "pipeline/execution.h"
#include "pipeline/framebuffer.h"
#include "pipeline/front_end.h"
#include "pipeline/instrumentation.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "pipeline/status.h"
#include "pipeline/tile_loop.h"
#include "pipeline/vertex_stage.h"

namespace rast {

// An indexed triangle list: every three indices name one triangle's vertices.
template <VertexShader VS, PixelShader PS>
struct DrawCall {
  std::span<const typename VS::Vertex> vertices;
  std::span<const uint32_t> indices;
  const VS& vertexShader;
  const PS& pixelShader;
};

// Checks what would make a draw invalid, before anything is drawn.
Status validateDraw(const Framebuffer& fb, const PipelineState& state, size_t vertexCount,
                    std::span<const uint32_t> indices);
// Its two parts: everything but the indices' values (draw checks those in the vertex stage's
// first pass over them, runVertexStage), and the first index out of range.
Status validateDrawState(const Framebuffer& fb, const PipelineState& state, size_t indexCount);
Status validateIndices(size_t vertexCount, std::span<const uint32_t> indices);

// Viewport, scissor and framebuffer, intersected: the only pixels a draw may touch.
PixelRect drawableRect(const Framebuffer& fb, const PipelineState& state);

// What a draw runs in place of its pixel shader when it writes no colour and the shader cannot
// discard: the back end then runs no shader at all, and this one reads no varying, so the front
// end carries none (no varying planes set up, smaller set-up triangles for binning and the back
// end to read). It is never called.
struct NoPixelShader {
  static constexpr int kVaryings = 0;
  static constexpr bool kMayDiscard = false;
  PixelResult operator()(const Fragment<0>&) const { return {}; }
};

// Whether the front end bins each chunk of triangles in the task that set it up (TileBins::
// binChunk), from that core's cache, instead of in a pass of its own that reads every set-up
// triangle again. Only for draws of a few chunks per thread: a chunk is binned by one task, where
// build() splits draws of few chunks (W3's 32 full-screen triangles) into bands of tile rows.
// Either way the bins are the same. Called inside the draw's arena.
template <int N>
bool binWhileSettingUp(size_t triangles) {
  const size_t chunks = chunkCount(triangles, SetupTriangles<N>::kInputChunk);
  return chunks >= 2 * size_t(tbb::this_task_arena::max_concurrency());
}

// Renders the draw into `fb` and adds its counters to `stats`. On an error nothing is drawn.
// `exec` chooses threads and coverage kernel; no choice changes a bit of the output.
template <VertexShader VS, PixelShader PS>
Status draw(Framebuffer& fb, const PipelineState& state, const DrawCall<VS, PS>& call,
            PipelineStatistics& stats, const ExecutionOptions& exec = {}) {
  constexpr int N = PS::kVaryings;
  static_assert(N <= VS::kVaryings, "the pixel shader reads more varyings than the vertex shader writes");
  // A depth-only pass pays for no varying (W4: the bunny's normals). Its depth, counts and
  // statistics are the same either way: depth planes do not depend on the varyings, and no
  // counter counts them (tests/depth_only_test.cpp).
  if constexpr (N > 0 && !PS::kMayDiscard)
    if (!state.colorWrite) {
      const NoPixelShader none;
      return draw(fb, state,
                  DrawCall<VS, NoPixelShader>{call.vertices, call.indices, call.vertexShader, none},
                  stats, exec);
    }
  if (Status s = validateDrawState(fb, state, call.indices.size()); !s) return s;
  PipelineStatistics local;
  bool indicesInRange = true;
  tbb::task_arena arena(exec.threads > 0 ? exec.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    StageClock clock(exec.timings);
    TransformedVertices<N> transformed(exec.memory);
    // The vertex stage checks the indices in its first pass over them, before it shades: a
    // separate pass took W2 tiny-1 2 ms a frame, serially, to read its 25 MB of indices.
    indicesInRange =
        runVertexStage<VS, N>(call.vertexShader, call.vertices, call.indices, transformed, local);
    if (!indicesInRange) return;
    clock.lap(&StageTimings::vertex);

    const ScreenMapping mapping = ScreenMapping::forState(state);
    const int32_t sampleReach = SamplePattern::forCount(fb.samples()).reach(state.format);
    const SetupContext setup{mapping,        state.format,    drawableRect(fb, state),
                             state.cullMode, state.frontFace, state.fillRule,
                             sampleReach,    state.rasterMode};
    SetupTriangles<N> triangles;
    TileBins bins(fb.width(), fb.height(), exec.memory, exec.binLevels);
    // A lambda, not &SetupTriangles<N>::id: binning calls it per triangle, and a function
    // pointer is not inlined there.
    const auto id = [](size_t c, size_t i) { return SetupTriangles<PS::kVaryings>::id(c, i); };
    const bool floatMode = state.rasterMode == RasterMode::Float;
    const ClipPlanes planes = ClipPlanes::forState(state, mapping);
    if (binWhileSettingUp<N>(call.indices.size() / 3)) {
      // Each chunk binned by the task that set it up, from its cache (clipSetup then includes
      // binning; bin is the sort).
      bins.startChunks(chunkCount(call.indices.size() / 3, SetupTriangles<N>::kInputChunk));
      clipAndSetupAll(transformed, setup, planes, triangles, local, [&](size_t c) {
        bins.binChunk(c, triangles.chunks[c], state.format, sampleReach, id,
                      floatMode ? &triangles.floatChunks[c] : nullptr);
      });
      clock.lap(&StageTimings::clipSetup);
      if (exec.timings) ++exec.timings->drawsBinnedInSetup;
      bins.finishChunks(local);
    } else {
      clipAndSetupAll(transformed, setup, planes, triangles, local);
      clock.lap(&StageTimings::clipSetup);
      bins.build(triangles.chunks, state.format, sampleReach, id, local,
                 floatMode ? &triangles.floatChunks : nullptr);
    }
    local.binEntries += bins.entryCount();
    if (exec.capture) exec.capture->record(bins, triangles);
    clock.lap(&StageTimings::bin);

    runBackEnd(fb, state, bins, triangles, call.pixelShader, exec, local);
    clock.lap(&StageTimings::backEnd);
  });
  if (!indicesInRange) return validateIndices(call.vertices.size(), call.indices);
  stats += local;
  return Status::ok();
}

}  // namespace rast
