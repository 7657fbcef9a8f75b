// Fuzzes draw(): random pipeline state and a random indexed triangle stream, in clip or window
// space, in every fixed-point precision. Checks what must hold for any input:
//   * validateDraw either refuses the draw (and then nothing is touched) or it renders;
//   * the scalar reference kernel and the best SIMD kernel give bit-identical images, depth and
//     statistics, at one and two threads;
//   * the count image sums to merge.fragments_written, which never exceeds the covered samples.
// Any violation aborts, which libFuzzer reports as a crash with the input that caused it.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "pipeline/draw.h"

namespace {

using namespace rast;

struct FuzzVertex {
  glm::vec4 position;
  float varying;
};

struct FuzzVertexShader {
  using Vertex = FuzzVertex;
  static constexpr int kVaryings = 1;
  ShadedVertex<1> operator()(const Vertex& v) const { return {v.position, {v.varying}}; }
};

// Reads the varying and discards where it is negative, so interpolation and discard both run.
struct FuzzPixelShader {
  static constexpr int kVaryings = 1;
  static constexpr bool kMayDiscard = true;
  PixelResult operator()(const Fragment<1>& f) const {
    if (f.varyings[0] < 0) return PixelResult::discarded();
    return {glm::vec4(f.varyings[0], f.depth, float(f.primitiveId & 255) / 255.0f, 1.0f)};
  }
};

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "draw_fuzzer: %s\n", what);
  std::abort();
}

// A coordinate: raw float bits (NaN, infinities, denormals, huge values), a small value on a
// subpixel-ish grid (ties on samples and edges), or a value scaled by a power of two around the
// limits of fixed point and the near plane.
float coordinate(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: {
      const uint32_t bits = in.ConsumeIntegral<uint32_t>();
      float f;
      std::memcpy(&f, &bits, sizeof f);
      return f;
    }
    case 1:
      return float(in.ConsumeIntegralInRange<int>(-2048, 2048)) / 256.0f;
    case 2:
      return std::ldexp(float(in.ConsumeIntegralInRange<int>(-64, 64)) / 16.0f,
                        in.ConsumeIntegralInRange<int>(-60, 40));
    default:
      return in.ConsumeFloatingPoint<float>();
  }
}

struct Result {
  Status status = Status::ok();
  std::vector<PackedColor> color;
  std::vector<float> depth;
  std::vector<uint32_t> counts;
  PipelineStatistics stats;
};

Result render(int width, int height, const PipelineState& state,
              const std::vector<FuzzVertex>& vertices, const std::vector<uint32_t>& indices,
              const ExecutionOptions& exec) {
  Framebuffer fb(width, height, true);
  const bool reversed =
      state.depth.compare == CompareOp::Greater || state.depth.compare == CompareOp::GreaterEqual;
  fb.clear(glm::vec4(0, 0, 0, 1), reversed ? 0.0f : 1.0f);
  const std::vector<PackedColor> color0 = fb.colorPlane();
  const std::vector<float> depth0 = fb.depthPlane();
  Result r;
  const FuzzVertexShader vs;
  const FuzzPixelShader ps;
  r.status = draw(fb, state, DrawCall<FuzzVertexShader, FuzzPixelShader>{vertices, indices, vs, ps},
                  r.stats, exec);
  if (!r.status) {
    if (r.status.message().empty()) fail("an error without a message");
    if (fb.colorPlane() != color0 || std::memcmp(fb.depthPlane().data(), depth0.data(),
                                                 depth0.size() * sizeof(float)) != 0)
      fail("a refused draw changed the framebuffer");
    if (!(r.stats == PipelineStatistics{})) fail("a refused draw counted something");
  }
  r.color = fb.colorPlane();
  r.depth = fb.depthPlane();
  r.counts = fb.countPlane();
  return r;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  const int width = in.ConsumeIntegralInRange<int>(1, 40);
  const int height = in.ConsumeIntegralInRange<int>(1, 40);

  PipelineState state;
  const int fractionBits = in.ConsumeIntegralInRange<int>(0, 9);  // 0 and 9 are invalid
  state.format = fractionBits >= 1 && fractionBits <= 8
                     ? FixedPointFormat::withFractionBits(fractionBits)
                     : FixedPointFormat{28 - fractionBits, fractionBits};
  state.positionSpace = in.ConsumeBool() ? PositionSpace::Window : PositionSpace::Clip;
  if (in.ConsumeIntegralInRange<int>(0, 7) == 0) {
    // Anything at all, including viewports far beyond the fixed-point range: validateDraw's job.
    state.viewport = {in.ConsumeIntegral<int>(), in.ConsumeIntegral<int>(),
                      in.ConsumeIntegral<int>(), in.ConsumeIntegral<int>()};
  } else {
    state.viewport = {in.ConsumeIntegralInRange<int>(-8, 8), in.ConsumeIntegralInRange<int>(-8, 8),
                      in.ConsumeIntegralInRange<int>(1, 48), in.ConsumeIntegralInRange<int>(1, 48)};
  }
  if (in.ConsumeBool()) {
    const int x0 = in.ConsumeIntegralInRange<int>(-4, 44), y0 = in.ConsumeIntegralInRange<int>(-4, 44);
    state.scissor = PixelRect{x0, y0, x0 + in.ConsumeIntegralInRange<int>(-2, 44),
                              y0 + in.ConsumeIntegralInRange<int>(-2, 44)};
  }
  state.cullMode = CullMode(in.ConsumeIntegralInRange<int>(0, 2));
  state.frontFace = FrontFace(in.ConsumeIntegralInRange<int>(0, 1));
  state.depth.compare = CompareOp(in.ConsumeIntegralInRange<int>(0, 7));
  state.depth.write = in.ConsumeBool();
  state.depth.early = in.ConsumeBool();
  state.colorWrite = in.ConsumeBool();

  const size_t vertexCount = in.ConsumeIntegralInRange<size_t>(0, 24);
  std::vector<FuzzVertex> vertices(vertexCount);
  for (FuzzVertex& v : vertices) {
    const bool window = state.positionSpace == PositionSpace::Window;
    v.position = {coordinate(in), coordinate(in), window ? float(in.ConsumeIntegralInRange<int>(0, 8)) / 8.0f : coordinate(in),
                  window ? 1.0f : coordinate(in)};
    v.varying = float(in.ConsumeIntegralInRange<int>(-8, 8)) / 4.0f;
  }
  const size_t indexCount = in.ConsumeIntegralInRange<size_t>(0, 60);
  const bool anyIndex = in.ConsumeIntegralInRange<int>(0, 15) == 0;  // out of range: an error
  std::vector<uint32_t> indices(indexCount);
  for (uint32_t& i : indices)
    i = anyIndex || vertexCount == 0 ? in.ConsumeIntegral<uint32_t>()
                                     : in.ConsumeIntegralInRange<uint32_t>(0, uint32_t(vertexCount - 1));

  ExecutionOptions reference;
  reference.threads = 1;
  reference.coverage = availableCoverageKernels().front();  // the scalar int64 kernel
  const Result a = render(width, height, state, vertices, indices, reference);
  ExecutionOptions fast;
  fast.threads = 2;  // the machine may have fewer cores; oneTBB still splits the work
  const Result b = render(width, height, state, vertices, indices, fast);

  if (a.status.isOk() != b.status.isOk() || a.status.message() != b.status.message())
    fail("the kernel or thread count changed whether the draw is valid");
  if (a.color != b.color) fail("colour differs between the scalar and the SIMD kernel");
  if (!sameBits(a.depth, b.depth)) fail("depth differs between the scalar and the SIMD kernel");
  if (a.counts != b.counts) fail("counts differ between the scalar and the SIMD kernel");
  if (!(a.stats == b.stats)) fail("statistics differ between the scalar and the SIMD kernel");
  const uint64_t total = std::accumulate(a.counts.begin(), a.counts.end(), uint64_t{0});
  if (total != a.stats.fragmentsWritten) fail("the count image does not sum to fragments_written");
  if (a.stats.fragmentsWritten > a.stats.samplesCovered) fail("more fragments than samples");
  if (a.status && a.stats.inputTriangles != indices.size() / 3) fail("triangles went missing");
  return 0;
}
