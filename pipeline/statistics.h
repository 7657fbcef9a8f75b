// Per-draw counters, named by stage. Every counter is exact and independent of thread count.
#pragma once

#include <cstdint>
#include <array>
#include <string>
#include <utility>

namespace rast {

struct PipelineStatistics {
  // vertex
  uint64_t inputIndices = 0;
  uint64_t vertexShaderInvocations = 0;  // one per unique index (post-transform cache)
  // clip (triangles)
  uint64_t inputTriangles = 0;
  uint64_t clipNonFinite = 0;        // a NaN or infinite position: dropped
  uint64_t clipTrivialReject = 0;    // all vertices outside one viewport or depth plane
  uint64_t clipClipped = 0;          // crossed the near, far or guard-band planes
  uint64_t clipOutputTriangles = 0;  // triangles leaving the clipper (the unclipped ones too)
  uint64_t clipDegenerate = 0;       // clipped to a sliver that no longer projects (w -> 0)
  // Per clip plane, in the order they are applied (ClipPlanes::clip): polygons cut against it
  // (a vertex of the triangle lies beyond it) and polygons left after the cut.
  uint64_t clipWIn = 0, clipWOut = 0;
  uint64_t clipNearIn = 0, clipNearOut = 0;
  uint64_t clipFarIn = 0, clipFarOut = 0;
  uint64_t clipGuardLeftIn = 0, clipGuardLeftOut = 0;
  uint64_t clipGuardRightIn = 0, clipGuardRightOut = 0;
  uint64_t clipGuardTopIn = 0, clipGuardTopOut = 0;
  uint64_t clipGuardBottomIn = 0, clipGuardBottomOut = 0;
  // setup
  uint64_t setupCulledBack = 0;
  uint64_t setupCulledFront = 0;
  uint64_t setupZeroArea = 0;   // snapped vertices collinear
  // The bounding box holds no pixel centre inside viewport and scissor; or, fixed point and
  // single-sampled, a triangle under two pixels across covers none of the (at most 2x2) centres
  // its box holds.
  uint64_t setupNoSamples = 0;
  uint64_t setupTriangles = 0;  // passed setup
  // bin
  uint64_t binEntries = 0;               // (triangle, tile) pairs
  uint64_t tilesTriviallyRejected = 0;   // tiles in a bounding box that the corner test rejected
  // raster
  uint64_t tilesTriviallyAccepted = 0;   // every sample covered, no per-sample test
  uint64_t tilesPartial = 0;             // per-sample edge tests
  uint64_t samplesCovered = 0;
  // pixel / merge
  uint64_t depthTestsPassed = 0;
  uint64_t depthTestsFailed = 0;
  uint64_t pixelShaderInvocations = 0;
  uint64_t pixelHelperLanes = 0;  // quad lanes interpolated only for derivatives, never shaded
  uint64_t fragmentsDiscarded = 0;
  uint64_t fragmentsWritten = 0;  // passed every test; what the count image counts
  uint64_t samplesBlended = 0;    // samples merged with the stored colour by blending

  template <class F>
  void forEachCounter(F&& f) const;  // f(name, value) for every counter, "stage.counter"

  PipelineStatistics& operator+=(const PipelineStatistics& o);
  friend bool operator==(const PipelineStatistics&, const PipelineStatistics&) = default;
  std::string toJson(int indent = 2) const;
};

// Every counter with its name: the one list that JSON, tables and summation all use.
inline constexpr std::array<std::pair<const char*, uint64_t PipelineStatistics::*>, 39>
    kPipelineCounters = {{
    {"vertex.input_indices", &PipelineStatistics::inputIndices},
    {"vertex.shader_invocations", &PipelineStatistics::vertexShaderInvocations},
    {"clip.input_triangles", &PipelineStatistics::inputTriangles},
    {"clip.non_finite", &PipelineStatistics::clipNonFinite},
    {"clip.trivial_reject", &PipelineStatistics::clipTrivialReject},
    {"clip.clipped", &PipelineStatistics::clipClipped},
    {"clip.output_triangles", &PipelineStatistics::clipOutputTriangles},
    {"clip.degenerate", &PipelineStatistics::clipDegenerate},
    {"clip.w_in", &PipelineStatistics::clipWIn},
    {"clip.w_out", &PipelineStatistics::clipWOut},
    {"clip.near_in", &PipelineStatistics::clipNearIn},
    {"clip.near_out", &PipelineStatistics::clipNearOut},
    {"clip.far_in", &PipelineStatistics::clipFarIn},
    {"clip.far_out", &PipelineStatistics::clipFarOut},
    {"clip.guard_left_in", &PipelineStatistics::clipGuardLeftIn},
    {"clip.guard_left_out", &PipelineStatistics::clipGuardLeftOut},
    {"clip.guard_right_in", &PipelineStatistics::clipGuardRightIn},
    {"clip.guard_right_out", &PipelineStatistics::clipGuardRightOut},
    {"clip.guard_top_in", &PipelineStatistics::clipGuardTopIn},
    {"clip.guard_top_out", &PipelineStatistics::clipGuardTopOut},
    {"clip.guard_bottom_in", &PipelineStatistics::clipGuardBottomIn},
    {"clip.guard_bottom_out", &PipelineStatistics::clipGuardBottomOut},
    {"setup.culled_back", &PipelineStatistics::setupCulledBack},
    {"setup.culled_front", &PipelineStatistics::setupCulledFront},
    {"setup.zero_area", &PipelineStatistics::setupZeroArea},
    {"setup.no_samples", &PipelineStatistics::setupNoSamples},
    {"setup.triangles", &PipelineStatistics::setupTriangles},
    {"bin.entries", &PipelineStatistics::binEntries},
    {"bin.tiles_trivially_rejected", &PipelineStatistics::tilesTriviallyRejected},
    {"raster.tiles_trivially_accepted", &PipelineStatistics::tilesTriviallyAccepted},
    {"raster.tiles_partial", &PipelineStatistics::tilesPartial},
    {"raster.samples_covered", &PipelineStatistics::samplesCovered},
    {"merge.depth_passed", &PipelineStatistics::depthTestsPassed},
    {"merge.depth_failed", &PipelineStatistics::depthTestsFailed},
    {"pixel.shader_invocations", &PipelineStatistics::pixelShaderInvocations},
    {"pixel.helper_lanes", &PipelineStatistics::pixelHelperLanes},
    {"pixel.discarded", &PipelineStatistics::fragmentsDiscarded},
    {"merge.fragments_written", &PipelineStatistics::fragmentsWritten},
    {"merge.samples_blended", &PipelineStatistics::samplesBlended},
}};

// The per-plane counters of the clipper, indexed like ClipPlanes::clip: {in, out}.
inline constexpr std::array<std::pair<uint64_t PipelineStatistics::*, uint64_t PipelineStatistics::*>, 7>
    kClipPlaneCounters = {{
    {&PipelineStatistics::clipWIn, &PipelineStatistics::clipWOut},
    {&PipelineStatistics::clipNearIn, &PipelineStatistics::clipNearOut},
    {&PipelineStatistics::clipFarIn, &PipelineStatistics::clipFarOut},
    {&PipelineStatistics::clipGuardLeftIn, &PipelineStatistics::clipGuardLeftOut},
    {&PipelineStatistics::clipGuardRightIn, &PipelineStatistics::clipGuardRightOut},
    {&PipelineStatistics::clipGuardTopIn, &PipelineStatistics::clipGuardTopOut},
    {&PipelineStatistics::clipGuardBottomIn, &PipelineStatistics::clipGuardBottomOut},
}};

template <class F>
void PipelineStatistics::forEachCounter(F&& f) const {
  for (const auto& [name, member] : kPipelineCounters) f(name, this->*member);
}

}  // namespace rast
