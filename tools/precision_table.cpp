// precision_table: the precision laboratory's speed/accuracy table. Runs the benchmark workloads
// W1-W4 in every raster mode (fixed point with 1..8 subpixel bits, float mode) and measures, per
// mode: throughput; coverage against the exact reference rasterizer, both with the same snapping
// (must be zero for fixed point) and against the exact, unsnapped geometry; watertightness on the
// fan and grid cases; the worst interpolation error in ULPs. Adds the depth formats' throughput
// and their depth resolution, and pictures: per mode, the coverage difference from the exact
// geometry, and a strip of frames of a slowly moving edge (stair-stepping).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/workloads.h"
#include "pipeline/depth_format.h"
#include "pipeline/draw.h"
#include "pipeline/viewport.h"
#include "reference/exact_rasterizer.h"
#include "reference/interpolation_error.h"
#include "reference/watertight_cases.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/transform.h"
#include "shaders_cpp/window_space.h"

namespace {

using namespace rast;
using reference::WindowPoint;
using reference::WindowTriangle;

struct Options {
  std::string meshes;  // empty: the embedded low-resolution bunny for W1
  std::string out = "precision";
  int runs = 3;
  int threads = 0;
  bool withTiny1 = false;
};

struct Mode {
  std::string name;
  FixedPointFormat format;
  RasterMode raster;
};

std::vector<Mode> allModes() {
  std::vector<Mode> modes;
  for (int bits = 1; bits <= 8; ++bits)
    modes.push_back({std::to_string(bits) + (bits == 1 ? " bit" : " bits"),
                     FixedPointFormat::withFractionBits(bits), RasterMode::FixedPoint});
  modes.push_back({"float", FixedPointFormat::d16_8(), RasterMode::Float});
  return modes;
}

std::string fileTag(const Mode& m) {
  return m.raster == RasterMode::Float ? "float" : "bits" + std::to_string(m.format.fractionBits);
}

void progress(const std::string& what) { std::fprintf(stderr, "precision_table: %s\n", what.c_str()); }

// ---- Throughput.

struct Workloads {
  workloads::LitMeshScene bunny;
  std::vector<std::pair<std::string, workloads::WindowGeometry>> flat;  // W2 and W3
};

template <class Draw>
double medianMilliseconds(int runs, Draw&& draw) {
  draw();  // warm-up: allocations, page faults
  std::vector<double> ms;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    draw();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

struct Timing {
  std::string workload;
  double ms = 0;
  size_t triangles = 0;
};

std::vector<Timing> timeWorkloads(const Workloads& w, FixedPointFormat format, RasterMode mode,
                                  DepthFormat depth, const Options& o) {
  ScratchMemory memory;
  ExecutionOptions exec{o.threads, bestCoverageKernel()};
  exec.memory = &memory;
  Framebuffer fb(workloads::kFrameWidth, workloads::kFrameHeight);
  std::vector<Timing> out;
  for (const bool colorWrite : {true, false}) {  // W1, then W4
    PipelineState state = workloads::workloadState(fb.width(), fb.height(), PositionSpace::Clip);
    state.format = format;
    state.rasterMode = mode;
    state.depth.format = depth;
    state.colorWrite = colorWrite;
    const double ms = medianMilliseconds(o.runs, [&] {
      PipelineStatistics stats;
      fb.clear(workloads::kClearColor, workloads::kClearDepth);
      (void)workloads::drawLitMesh(fb, state, w.bunny, stats, exec);
    });
    out.push_back({colorWrite ? "W1" : "W4", ms, w.bunny.mesh.triangleCount()});
  }
  for (const auto& [name, geometry] : w.flat) {
    PipelineState state = workloads::workloadState(fb.width(), fb.height(), PositionSpace::Window);
    state.format = format;
    state.rasterMode = mode;
    state.depth.format = depth;
    const double ms = medianMilliseconds(o.runs, [&] {
      PipelineStatistics stats;
      fb.clear(workloads::kClearColor, workloads::kClearDepth);
      (void)workloads::drawFlatGeometry(fb, state, geometry, stats, exec);
    });
    out.push_back({name, ms, geometry.triangleCount()});
  }
  // W1, W2..., W3..., W4 in the order of the workloads document.
  std::rotate(out.begin() + 1, out.begin() + 2, out.end());
  return out;
}

// ---- Coverage against the exact reference, at a modest resolution.

constexpr int kCoverageWidth = 640, kCoverageHeight = 360;

struct CoverageCase {
  std::string name;
  PositionSpace space;
  std::vector<WindowTriangle> window;  // double window positions, as setup computes them
  // What the pipeline draws.
  std::vector<MeshVertex> meshVertices;
  std::vector<uint32_t> indices;
  glm::mat4 viewProjection{1.0f};
  workloads::WindowGeometry flat;
};

CoverageCase bunnyCase(const Mesh& mesh) {
  CoverageCase c;
  c.name = "W1 bunny";
  c.space = PositionSpace::Clip;
  c.meshVertices = mesh.vertices;
  c.indices = mesh.indices;
  c.viewProjection = frameMesh(mesh).viewProjection(float(kCoverageWidth) / kCoverageHeight);
  PipelineState state;
  state.viewport = {0, 0, kCoverageWidth, kCoverageHeight};
  const ScreenMapping mapping = ScreenMapping::forState(state);
  const TransformVertexShader vs{c.viewProjection};
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    WindowTriangle w;
    for (int k = 0; k < 3; ++k) {
      const WindowPosition p = mapping.toWindow(glm::dvec4(vs(mesh.vertices[mesh.indices[t + k]]).position));
      w[k] = {p.x, p.y};
    }
    c.window.push_back(w);
  }
  return c;
}

CoverageCase gridCase(double area) {
  CoverageCase c;
  c.name = "W2 tiny-" + std::to_string(int(area));
  c.space = PositionSpace::Window;
  c.flat = workloads::triangleGrid(area, kCoverageWidth, kCoverageHeight, workloads::kTinyTriangleDepth);
  for (size_t t = 0; t + 2 < c.flat.indices.size(); t += 3) {
    WindowTriangle w;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = c.flat.vertices[c.flat.indices[t + k]].position;
      w[k] = {p.x, p.y};
    }
    c.window.push_back(w);
  }
  return c;
}

std::vector<uint32_t> pipelineCounts(const CoverageCase& c, const Mode& mode) {
  PipelineState state;
  state.viewport = {0, 0, kCoverageWidth, kCoverageHeight};
  state.positionSpace = c.space;
  state.format = mode.format;
  state.rasterMode = mode.raster;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  Framebuffer fb(kCoverageWidth, kCoverageHeight, true);
  PipelineStatistics stats;
  const ConstantColorShader ps;
  Status s = Status::ok();
  if (c.space == PositionSpace::Clip) {
    const TransformVertexShader vs{c.viewProjection};
    s = draw(fb, state, DrawCall<TransformVertexShader, ConstantColorShader>{c.meshVertices, c.indices, vs, ps}, stats);
  } else {
    const WindowSpaceVertexShader vs;
    s = draw(fb, state, DrawCall<WindowSpaceVertexShader, ConstantColorShader>{c.flat.vertices, c.flat.indices, vs, ps}, stats);
  }
  if (!s) progress("draw failed: " + s.message());
  return fb.countPlane();
}

// The exact geometry is that of the float-rounded window positions (what float mode takes; within
// 2^-16 pixel of the double ones at this size), always exactly representable on a grid.
std::vector<WindowTriangle> floatRounded(const std::vector<WindowTriangle>& in) {
  std::vector<WindowTriangle> out;
  for (const WindowTriangle& t : in) out.push_back(reference::roundedToFloat(t));
  return out;
}

struct CoverageResult {
  uint64_t sameSnapMismatches = 0;  // fixed point: against the reference with the same snapping
  uint64_t missing = 0, extra = 0;  // against the exact geometry (net count per pixel)
  uint64_t samples = 0;             // covered samples of the exact geometry
};

void writeDifferenceImage(const std::vector<uint32_t>& counts, const std::vector<uint32_t>& exact,
                          const std::string& path) {
  Framebuffer img(kCoverageWidth, kCoverageHeight);
  for (size_t i = 0; i < counts.size(); ++i) {
    glm::vec4 c(0, 0, 0, 1);
    if (counts[i] < exact[i]) c = {1.0f, 0.25f, 0.2f, 1};      // missing: red
    else if (counts[i] > exact[i]) c = {0.2f, 0.9f, 1.0f, 1};  // extra: cyan
    else if (exact[i] > 0) c = {0.22f, 0.22f, 0.22f, 1};       // agree, covered: grey
    img.colorPlane()[i] = packColor(c);
  }
  if (Status s = writeColorImage(img, path); !s) progress(s.message());
}

// ---- Watertightness on the fan and grid cases of tests/watertight_test.cpp.

struct WatertightResult {
  reference::WatertightViolations origin, far;
};

reference::WatertightViolations violations(const reference::Mesh2D& m, int64_t unit, const Mode& mode, int offset) {
  constexpr int kSize = 64;
  const int width = offset + kSize;
  reference::Mesh2D shifted = m;
  for (reference::SubPoint& p : shifted.vertices) p.x += int64_t(offset) * unit;
  std::vector<WindowVertex> vertices;
  for (const reference::SubPoint& p : shifted.vertices)
    vertices.push_back({glm::vec3(float(double(p.x) / unit), float(double(p.y) / unit), 0.5f)});
  PipelineState state;
  state.viewport = {0, 0, width, kSize};
  state.positionSpace = PositionSpace::Window;
  state.format = mode.format;
  state.rasterMode = mode.raster;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  Framebuffer fb(width, kSize, true);
  PipelineStatistics stats;
  const WindowSpaceVertexShader vs;
  const ConstantColorShader ps;
  (void)draw(fb, state, DrawCall<WindowSpaceVertexShader, ConstantColorShader>{vertices, shifted.indices, vs, ps}, stats);
  return reference::countViolations(reference::strictlyInsideUnion(shifted, unit, width, kSize), fb.countPlane());
}

WatertightResult watertightness(const Mode& mode) {
  // Vertices on the mode's own subpixel grid (snapping moves none); float mode on 1/256.
  const int bits = mode.raster == RasterMode::Float ? 8 : mode.format.fractionBits;
  const int64_t unit = int64_t{1} << bits;
  WatertightResult r;
  for (const bool fans : {true, false}) {
    std::mt19937_64 rng(fans ? 0xfa70000 + bits : 0x961d0000 + bits);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int iter = 0; iter < 40; ++iter) {
      reference::Mesh2D m;
      if (fans) {
        m = reference::randomFan(rng, unit, 64, 64);
      } else {
        const double cell = iter % 4 == 0 ? 0.3 + u(rng) : 2.0 + 10.0 * u(rng);
        m = reference::randomGrid(rng, unit, 64, 64, iter % 5 != 0, cell);
      }
      for (const int offset : {0, 4096}) {
        const reference::WatertightViolations v = violations(m, unit, mode, offset);
        reference::WatertightViolations& sum = offset == 0 ? r.origin : r.far;
        sum.gaps += v.gaps;
        sum.doubleHits += v.doubleHits;
        sum.interior += v.interior;
      }
    }
  }
  return r;
}

// ---- Interpolation error: random perspective triangles, well-shaped and near the near plane.

reference::InterpolationErrors interpolationErrors(const Mode& mode) {
  std::mt19937_64 rng(0x1e7e9002);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr int kSize = 64;
  reference::InterpolationErrors all;
  for (int i = 0; i < 400; ++i) {
    std::array<ShadedVertex<2>, 3> t;
    for (int k = 0; k < 3; ++k) {
      const bool nearPlane = i % 2 && k == 0;
      const double w = nearPlane ? 0.005 + 0.015 * u(rng) : 0.5 + 3.5 * u(rng);
      const double z = nearPlane ? -1 + 2 * std::pow(10.0, -3 - 2 * u(rng)) : -0.95 + 1.9 * u(rng);
      const double wx = -8 + 80 * u(rng), wy = -8 + 80 * u(rng), h = kSize / 2.0;
      t[k] = {glm::vec4(glm::dvec4((wx - h) / h * w, -(wy - h) / h * w, z * w, w)),
              {float(u(rng)), float(1000.0 + u(rng))}};
    }
    PipelineState state;
    state.format = mode.format;
    state.rasterMode = mode.raster;
    reference::InterpolationErrors e;
    if (Status s = reference::measureInterpolation(t, state, kSize, kSize, e); !s) progress(s.message());
    if (!e.clipped) all.add(e);
  }
  return all;
}

// ---- The moving edge: a shallow edge (slope 1/8) moved down by 1/16 pixel per frame.

void writeStairSteps(const std::string& path) {
  constexpr int kW = 16, kH = 8, kFrames = 16, kScale = 6, kGap = 2;
  const std::vector<Mode> rows = {{"1 bit", FixedPointFormat::withFractionBits(1), RasterMode::FixedPoint},
                                  {"4 bits", FixedPointFormat::withFractionBits(4), RasterMode::FixedPoint},
                                  {"8 bits", FixedPointFormat::withFractionBits(8), RasterMode::FixedPoint},
                                  {"float", FixedPointFormat::d16_8(), RasterMode::Float}};
  const int width = kFrames * (kW * kScale + kGap) - kGap, height = int(rows.size()) * (kH * kScale + kGap) - kGap;
  Framebuffer img(width, height);
  img.clear(glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), 1.0f);
  for (size_t r = 0; r < rows.size(); ++r)
    for (int f = 0; f < kFrames; ++f) {
      const double y0 = 2.3 + f / 16.0;
      const WindowTriangle t = {{{-4.0, y0}, {20.0, y0 + 3.0}, {-4.0, 40.0}}};
      std::vector<WindowTriangle> one = {t};
      PipelineState state;
      state.viewport = {0, 0, kW, kH};
      state.positionSpace = PositionSpace::Window;
      state.format = rows[r].format;
      state.rasterMode = rows[r].raster;
      state.depth.compare = CompareOp::Always;
      state.depth.write = false;
      Framebuffer fb(kW, kH, true);
      PipelineStatistics stats;
      const std::vector<WindowVertex> v = {{{float(t[0].x), float(t[0].y), 0.5f}},
                                           {{float(t[1].x), float(t[1].y), 0.5f}},
                                           {{float(t[2].x), float(t[2].y), 0.5f}}};
      const std::vector<uint32_t> idx = {0, 1, 2};
      const WindowSpaceVertexShader vs;
      const ConstantColorShader ps;
      (void)draw(fb, state, DrawCall<WindowSpaceVertexShader, ConstantColorShader>{v, idx, vs, ps}, stats);
      const reference::CoverageCounts exact = reference::rasterizeCounts(
          floatRounded(one), kW, kH, {false, rows[r].format, reference::SampleRule::TopLeft});
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          const bool got = fb.count(x, y) > 0, want = exact.counts[size_t(y) * kW + x] > 0;
          const glm::vec4 c = got && want ? glm::vec4(1, 1, 1, 1)
                              : got       ? glm::vec4(0.2f, 0.9f, 1.0f, 1)   // extra: cyan
                              : want      ? glm::vec4(1.0f, 0.25f, 0.2f, 1)  // missing: red
                                          : glm::vec4(0, 0, 0, 1);
          for (int sy = 0; sy < kScale; ++sy)
            for (int sx = 0; sx < kScale; ++sx) {
              const int px = f * (kW * kScale + kGap) + x * kScale + sx;
              const int py = int(r) * (kH * kScale + kGap) + y * kScale + sy;
              img.colorPlane()[img.index(px, py)] = packColor(c);
            }
        }
    }
  if (Status s = writeColorImage(img, path); !s) progress(s.message());
}

// ---- Output.

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}
std::string general(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

int run(const Options& o) {
  std::filesystem::create_directories(o.out);
  Workloads w;
  if (o.meshes.empty()) {
    w.bunny.mesh = embeddedBunny();
    w.bunny.viewProjection = frameMesh(w.bunny.mesh).viewProjection(
        float(workloads::kFrameWidth) / float(workloads::kFrameHeight));
  } else if (Status s = workloads::loadLitMeshScene(o.meshes + "/bunny.obj", workloads::kFrameWidth,
                                                    workloads::kFrameHeight, w.bunny);
             !s) {
    std::fprintf(stderr, "precision_table: %s\n", s.message().c_str());
    return 1;
  }
  for (const int area : workloads::kTinyTriangleAreas) {
    if (area == 1 && !o.withTiny1) continue;
    w.flat.push_back({"W2 tiny-" + std::to_string(area),
                      workloads::triangleGrid(area, workloads::kFrameWidth, workloads::kFrameHeight,
                                              workloads::kTinyTriangleDepth)});
  }
  using workloads::LayerOrder, workloads::LayerShape;
  w.flat.push_back({"W3 front-to-back", workloads::overdrawLayers(workloads::kFrameWidth, workloads::kFrameHeight,
                                                                  LayerOrder::FrontToBack, LayerShape::Quad)});
  w.flat.push_back({"W3 back-to-front", workloads::overdrawLayers(workloads::kFrameWidth, workloads::kFrameHeight,
                                                                  LayerOrder::BackToFront, LayerShape::Quad)});

  std::vector<CoverageCase> cases = {bunnyCase(embeddedBunny()), gridCase(1), gridCase(10), gridCase(100)};
  // The exact geometry's coverage is the same for every mode.
  std::vector<std::vector<uint32_t>> exactCounts;
  for (const CoverageCase& c : cases) {
    const reference::CoverageCounts e = reference::rasterizeCounts(
        floatRounded(c.window), kCoverageWidth, kCoverageHeight, {false, {}, reference::SampleRule::TopLeft});
    if (e.undecidable) progress(c.name + ": " + std::to_string(e.undecidable) + " triangles not representable exactly");
    exactCounts.push_back(e.counts);
  }

  const std::vector<Mode> modes = allModes();
  std::ostringstream speed, accuracy, csv;
  // Column order of timeWorkloads: W1, W2 and W3 as listed, W4.
  std::vector<std::string> header = {"W1"};
  for (const auto& f : w.flat) header.push_back(f.first);
  header.push_back("W4");
  speed << "| mode | W1 Mtri/s |";
  for (const std::string& name : header) speed << " " << name << " |";
  speed << "\n|---|---|";
  for (size_t i = 0; i < header.size(); ++i) speed << "---|";
  speed << "\n";
  accuracy << "| mode | coverage ≠ reference, same snapping | missing / extra vs exact geometry | "
              "gaps / double hits, origin | gaps / double hits, x + 4096 | depth error (scale ULPs) | "
              "varying error (scale ULPs) | worst varying error (value ULPs) |\n"
              "|---|---|---|---|---|---|---|---|\n";
  csv << "mode,depth_format";
  for (const std::string& name : header) csv << "," << name << " ms";
  csv << ",w1_mtri_per_s,coverage_mismatch_same_snapping,missing_vs_exact,extra_vs_exact,exact_samples,"
         "gaps_origin,double_hits_origin,gaps_far,double_hits_far,depth_scale_ulps,varying_scale_ulps,"
         "varying_value_ulps\n";

  for (size_t mi = 0; mi < modes.size(); ++mi) {
    const Mode& mode = modes[mi];
    const std::string step = "[" + std::to_string(mi + 1) + "/" + std::to_string(modes.size()) + "] " + mode.name + ": ";
    progress(step + "timing");
    const std::vector<Timing> timings = timeWorkloads(w, mode.format, mode.raster, DepthFormat::Float32, o);
    progress(step + "coverage against the exact reference");
    CoverageResult cov;
    for (size_t ci = 0; ci < cases.size(); ++ci) {
      const std::vector<uint32_t> counts = pipelineCounts(cases[ci], mode);
      if (mode.raster == RasterMode::FixedPoint) {
        const reference::CoverageCounts same = reference::rasterizeCounts(
            cases[ci].window, kCoverageWidth, kCoverageHeight, {true, mode.format, reference::SampleRule::TopLeft});
        for (size_t i = 0; i < counts.size(); ++i)
          cov.sameSnapMismatches += counts[i] > same.counts[i] ? counts[i] - same.counts[i] : same.counts[i] - counts[i];
      }
      for (size_t i = 0; i < counts.size(); ++i) {
        const uint32_t e = exactCounts[ci][i];
        cov.missing += counts[i] < e ? e - counts[i] : 0;
        cov.extra += counts[i] > e ? counts[i] - e : 0;
        cov.samples += e;
      }
      if (ci == 0) writeDifferenceImage(counts, exactCounts[0], o.out + "/coverage_diff_" + fileTag(mode) + ".png");
    }
    progress(step + "watertightness");
    const WatertightResult wt = watertightness(mode);
    progress(step + "interpolation error");
    const reference::InterpolationErrors ie = interpolationErrors(mode);
    const double varyingScale = std::max(ie.varyings[0].scaleUlps, ie.varyings[1].scaleUlps);
    const double varyingValue = std::max(ie.varyings[0].valueUlps, ie.varyings[1].valueUlps);

    const double w1 = timings[0].ms;
    speed << "| " << mode.name << " | " << fixed(timings[0].triangles / (w1 * 1e3), 2) << " |";
    for (const Timing& t : timings) speed << " " << fixed(t.ms, 1) << " |";
    speed << "\n";
    accuracy << "| " << mode.name << " | "
             << (mode.raster == RasterMode::Float ? std::string("n/a (no snapping)") : std::to_string(cov.sameSnapMismatches))
             << " | " << cov.missing << " / " << cov.extra << " | " << wt.origin.gaps << " / "
             << wt.origin.doubleHits << " | " << wt.far.gaps << " / " << wt.far.doubleHits << " | "
             << fixed(ie.depth.scaleUlps, 2) << " | " << fixed(varyingScale, 2) << " | "
             << general(varyingValue) << " |\n";
    csv << mode.name << ",float32";
    for (const Timing& t : timings) csv << "," << fixed(t.ms, 3);
    csv << "," << fixed(timings[0].triangles / (w1 * 1e3), 4) << ","
        << (mode.raster == RasterMode::Float ? std::string("") : std::to_string(cov.sameSnapMismatches)) << ","
        << cov.missing << "," << cov.extra << "," << cov.samples << "," << wt.origin.gaps << ","
        << wt.origin.doubleHits << "," << wt.far.gaps << "," << wt.far.doubleHits << ","
        << fixed(ie.depth.scaleUlps, 3) << "," << fixed(varyingScale, 3) << "," << general(varyingValue) << "\n";
  }

  // Depth formats: throughput at 8 bits, and the resolution of a perspective projection.
  for (const DepthFormat df : {DepthFormat::Unorm24, DepthFormat::Unorm16}) {
    progress(std::string("depth format ") + std::string(depthFormatName(df)) + ": timing");
    const std::vector<Timing> timings = timeWorkloads(w, FixedPointFormat::d16_8(), RasterMode::FixedPoint, df, o);
    const std::string name = "8 bits, " + std::string(depthFormatName(df)) + " depth";
    speed << "| " << name << " | " << fixed(timings[0].triangles / (timings[0].ms * 1e3), 2) << " |";
    csv << "8 bits," << depthFormatName(df);
    for (const Timing& t : timings) speed << " " << fixed(t.ms, 1) << " |", csv << "," << fixed(t.ms, 3);
    csv << "," << fixed(timings[0].triangles / (timings[0].ms * 1e3), 4) << ",,,,,,,,,,,\n";
    speed << "\n";
  }
  std::ostringstream depth;
  const double nearPlane = 0.1, farPlane = 1000.0;
  depth << "| eye distance |";
  for (const DepthFormat df : {DepthFormat::Float32, DepthFormat::Unorm24, DepthFormat::Unorm16})
    for (const bool reversed : {false, true})
      depth << " " << depthFormatName(df) << (reversed ? " reversed" : " standard") << " |";
  depth << "\n|---|---|---|---|---|---|---|\n";
  for (const double d : {1.0, 10.0, 100.0, 500.0}) {
    depth << "| " << general(d) << " |";
    for (const DepthFormat df : {DepthFormat::Float32, DepthFormat::Unorm24, DepthFormat::Unorm16})
      for (const bool reversed : {false, true})
        depth << " " << general(depthResolution(df, {nearPlane, farPlane, reversed}, d)) << " |";
    depth << "\n";
  }

  progress("pictures");
  writeStairSteps(o.out + "/stair_steps.png");

  std::ofstream md(o.out + "/precision_table.md");
  md << "Speed (ms per frame, 1920x1080, median of " << o.runs << " runs; W1 Mtri/s = W1's triangles / "
     << "its time):\n\n" << speed.str() << "\nAccuracy (" << kCoverageWidth << "x" << kCoverageHeight
     << " coverage of the bunny and the tiny-1/10/100 grids; 80 fans and grids; 400 perspective "
        "triangles):\n\n"
     << accuracy.str() << "\nDepth resolution (smallest separation resolved for sure, near "
     << nearPlane << ", far " << farPlane << ", scene units):\n\n" << depth.str();
  std::ofstream(o.out + "/precision_table.csv") << csv.str();
  std::ifstream in(o.out + "/precision_table.md");
  std::printf("%s", std::string(std::istreambuf_iterator<char>(in), {}).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The precision laboratory: speed and accuracy of every raster mode"};
  Options o;
  app.add_option("--meshes", o.meshes, "folder with bunny.obj for W1 (default: the embedded 3,674-triangle bunny)")
      ->check(CLI::ExistingDirectory);
  app.add_option("--out", o.out, "folder for the table (.md, .csv) and pictures")->capture_default_str();
  app.add_option("--runs", o.runs, "timed runs per workload (median)")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--threads", o.threads, "worker threads (0: all)")->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_flag("--with-tiny-1", o.withTiny1, "also time W2 tiny-1 (about 2 s a frame)");
  CLI11_PARSE(app, argc, argv);
  return run(o);
}
