// Texture sampling per filter (samples per second, one thread), and the shadow-mapped
// Blinn-Phong default scene (light pass + camera pass) against the plain Lambert one at 1920x1080.
#include <benchmark/benchmark.h>

#include <random>

#include "pipeline/sampler.h"
#include "scene/scene.h"
#include "scene/shadow_pass.h"
#include "shaders_cpp/textured.h"

namespace rast {
namespace {

const Texture& benchTexture() {
  static const Texture t = [] {
    Texture tex;
    (void)checkerboardTexture(1024, 16, glm::vec4(0.9f, 0.9f, 0.9f, 1), glm::vec4(0.1f, 0.2f, 0.3f, 1), tex);
    return tex;
  }();
  return t;
}

// Random coordinates over a few repeats and levels of detail over the chain: sampling without
// the cache locality of a real footprint walk, so this is a lower bound on throughput.
void BM_TextureSample(benchmark::State& state) {
  const TextureFilter filter = TextureFilter(state.range(0));
  const TextureSampler sampler(benchTexture(), {filter, AddressMode::Repeat, AddressMode::Repeat});
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uv(-2.0f, 2.0f), lod(0.0f, 6.0f);
  std::vector<glm::vec3> queries(4096);
  for (glm::vec3& q : queries) q = {uv(rng), uv(rng), lod(rng)};
  glm::vec4 sum(0.0f);
  for (auto _ : state) {
    for (const glm::vec3& q : queries) sum += sampler.sample({q.x, q.y}, q.z);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(queries.size()));
  state.SetLabel(filter == TextureFilter::Nearest    ? "nearest"
                 : filter == TextureFilter::Bilinear ? "bilinear"
                                                     : "trilinear");
}
BENCHMARK(BM_TextureSample)->Arg(int(TextureFilter::Nearest))->Arg(int(TextureFilter::Bilinear))
    ->Arg(int(TextureFilter::Trilinear));

// The default scene, 1920x1080, one thread. Arg 0: Lambert; 1: shadow-mapped Blinn-Phong
// (2048x2048 map, 3x3 PCF), the light pass included.
void BM_DefaultSceneShading(benchmark::State& state) {
  const Scene scene = defaultScene();
  PipelineState ps;
  ps.viewport = {0, 0, 1920, 1080};
  Framebuffer fb(1920, 1080);
  ExecutionOptions exec;
  exec.threads = 1;
  const ShadingMode mode = state.range(0) ? ShadingMode::BlinnPhong : ShadingMode::Lambert;
  for (auto _ : state) {
    PipelineStatistics stats;
    if (!renderScene(scene, fb, ps, mode, stats, exec)) state.SkipWithError("render failed");
    benchmark::ClobberMemory();
  }
  state.SetLabel(state.range(0) ? "blinn-phong + shadow map" : "lambert");
}
BENCHMARK(BM_DefaultSceneShading)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The light pass alone (2048x2048, depth only), to split the ratio above.
void BM_ShadowLightPass(benchmark::State& state) {
  const Scene scene = defaultScene();
  glm::vec3 lo, hi;
  sceneBounds(scene, lo, hi);
  glm::mat4 lightVP;
  if (!fitLightViewProjection(sceneLight(scene), lo, hi, lightVP)) state.SkipWithError("fit failed");
  Framebuffer map(2048, 2048);
  ExecutionOptions exec;
  exec.threads = 1;
  for (auto _ : state) {
    PipelineStatistics stats;
    if (!renderShadowMap(scene, lightVP, map, stats, exec)) state.SkipWithError("render failed");
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ShadowLightPass)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rast
