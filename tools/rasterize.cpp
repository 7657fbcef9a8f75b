// rasterize: renders the built-in default scene, an OBJ mesh or a window-space triangle list to
// images (colour, depth, per-pixel fragment count) and writes the pipeline statistics as JSON.
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include "pipeline/draw.h"
#include "scene/scene.h"
#include "scene/triangle_list.h"
#include "shaders_cpp/constant_color.h"
#include "shaders_cpp/depth_visualizer.h"
#include "shaders_cpp/triangle_id.h"
#include "shaders_cpp/window_space.h"

namespace {

using namespace rast;

struct Options {
  std::string input;        // empty: the built-in default scene
  std::string inputKind = "auto";
  int width = 960, height = 540;
  int subpixelBits = 4;
  std::string cull = "none", frontFace = "ccw", depthCompare = "less", shading;
  bool noDepthWrite = false;
  int threads = 0;
  std::string coverageKernel = "auto";
  bool listKernels = false;
  std::string output, depthOutput, countOutput, statsOutput;
  std::vector<float> eye, target;
  float fov = 45.0f, nearPlane = 0.0f, farPlane = 0.0f;
};

int fail(const std::string& message) {
  std::fprintf(stderr, "rasterize: %s\n", message.c_str());
  return 1;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

const std::map<std::string, CompareOp> kCompareOps = {
    {"never", CompareOp::Never},       {"less", CompareOp::Less},
    {"equal", CompareOp::Equal},       {"less-equal", CompareOp::LessEqual},
    {"greater", CompareOp::Greater},   {"not-equal", CompareOp::NotEqual},
    {"greater-equal", CompareOp::GreaterEqual}, {"always", CompareOp::Always}};
const std::map<std::string, CullMode> kCullModes = {
    {"none", CullMode::None}, {"back", CullMode::Back}, {"front", CullMode::Front}};
const std::map<std::string, FrontFace> kFrontFaces = {
    {"ccw", FrontFace::CounterClockwise}, {"cw", FrontFace::Clockwise}};

template <class PS>
Status drawTriangleList(Framebuffer& fb, const PipelineState& state,
                        const std::vector<WindowVertex>& vertices, const PS& shader,
                        PipelineStatistics& stats, const ExecutionOptions& exec) {
  std::vector<uint32_t> indices(vertices.size());
  for (uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
  const WindowSpaceVertexShader vs;
  return draw(fb, state, DrawCall<WindowSpaceVertexShader, PS>{vertices, indices, vs, shader},
              stats, exec);
}

int run(const Options& o) {
  if (o.listKernels) {
    for (const CoverageKernel& k : availableCoverageKernels()) std::printf("%s\n", k.name.c_str());
    return 0;
  }
  ExecutionOptions exec;
  exec.threads = o.threads;
  if (!findCoverageKernel(o.coverageKernel, exec.coverage))
    return fail("coverage kernel '" + o.coverageKernel +
                "' is not available on this machine (see --list-kernels)");
  PipelineState state;
  state.viewport = {0, 0, o.width, o.height};
  state.format = FixedPointFormat::withFractionBits(o.subpixelBits);
  state.cullMode = kCullModes.at(o.cull);
  state.frontFace = kFrontFaces.at(o.frontFace);
  state.depth.compare = kCompareOps.at(o.depthCompare);
  state.depth.write = !o.noDepthWrite;

  std::string kind = o.inputKind;
  if (kind == "auto")
    kind = o.input.empty() ? "default" : (endsWith(o.input, ".obj") ? "obj" : "triangles");

  Framebuffer fb(o.width, o.height, !o.countOutput.empty());
  PipelineStatistics stats;
  const bool reversed =
      state.depth.compare == CompareOp::Greater || state.depth.compare == CompareOp::GreaterEqual;

  if (kind == "triangles") {
    std::vector<WindowVertex> vertices;
    if (Status s = loadTriangleList(o.input, vertices); !s) return fail(s.message());
    state.positionSpace = PositionSpace::Window;
    fb.clear(glm::vec4(0, 0, 0, 1), reversed ? 0.0f : 1.0f);
    const std::string shading = o.shading.empty() ? "constant" : o.shading;
    Status s = Status::ok();
    if (shading == "constant")
      s = drawTriangleList(fb, state, vertices, ConstantColorShader{}, stats, exec);
    else if (shading == "triangle-id")
      s = drawTriangleList(fb, state, vertices, TriangleIdShader{}, stats, exec);
    else if (shading == "depth")
      s = drawTriangleList(fb, state, vertices, DepthVisualizerShader{}, stats, exec);
    else
      return fail("shading '" + shading +
                  "' needs normals; triangle lists take constant, triangle-id or depth");
    if (!s) return fail(s.message());
  } else {
    Scene scene;
    if (kind == "default") {
      scene = defaultScene();
    } else {
      SceneObject object;
      if (Status s = loadObj(o.input, object.mesh); !s) return fail(s.message());
      scene.camera = frameMesh(object.mesh, o.fov);
      scene.lightPosition = scene.camera.eye + glm::vec3(0.35f, 0.55f, 0.76f) *
                                                   glm::distance(scene.camera.eye, scene.camera.target);
      scene.background = {0.1f, 0.1f, 0.12f, 1.0f};
      scene.objects.push_back(std::move(object));
    }
    if (!o.eye.empty()) scene.camera.eye = {o.eye[0], o.eye[1], o.eye[2]};
    if (!o.target.empty()) scene.camera.target = {o.target[0], o.target[1], o.target[2]};
    scene.camera.fovYDegrees = o.fov;
    if (o.nearPlane > 0) scene.camera.nearPlane = o.nearPlane;
    if (o.farPlane > 0) scene.camera.farPlane = o.farPlane;
    if (!(scene.camera.nearPlane < scene.camera.farPlane))
      return fail("--near must be smaller than --far");
    ShadingMode mode = ShadingMode::Lambert;
    if (!o.shading.empty() && !parseShadingMode(o.shading, mode))
      return fail("unknown shading '" + o.shading + "'");
    if (Status s = renderScene(scene, fb, state, mode, stats, exec); !s) return fail(s.message());
  }

  if (!o.output.empty())
    if (Status s = writeColorImage(fb, o.output); !s) return fail(s.message());
  if (!o.depthOutput.empty())
    if (Status s = writeDepthImage(fb, o.depthOutput); !s) return fail(s.message());
  if (!o.countOutput.empty())
    if (Status s = writeCountImage(fb, o.countOutput); !s) return fail(s.message());
  if (!o.statsOutput.empty()) {
    std::ofstream f(o.statsOutput);
    if (!f || !(f << stats.toJson() << "\n")) return fail("cannot write '" + o.statsOutput + "'");
  }
  std::printf("%s: %llu triangles in, %llu set up, %llu fragments written (%s, %dx%d)\n",
              kind == "default" ? "default scene" : o.input.c_str(),
              (unsigned long long)stats.inputTriangles, (unsigned long long)stats.setupTriangles,
              (unsigned long long)stats.fragmentsWritten, state.format.name().c_str(), o.width,
              o.height);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Renders a scene with the tiled fixed-point rasterizer.\n"
               "With no input, renders the built-in default scene."};
  app.add_option("input", o.input, "OBJ mesh (.obj) or window-space triangle list (any other name)");
  app.add_option("--input-kind", o.inputKind, "How to read the input")
      ->check(CLI::IsMember({"auto", "obj", "triangles"}));
  app.add_option("--width", o.width, "Image width in pixels")->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "Image height in pixels")->check(CLI::Range(1, 16384));
  app.add_option("--subpixel-bits", o.subpixelBits,
                 "Fraction bits F, 1..8: (28-F).F fixed point (4: 24.4), except 8: 16.8")
      ->check(CLI::Range(1, 8));
  app.add_option("--cull", o.cull, "Face culling")->check(CLI::IsMember({"none", "back", "front"}));
  app.add_option("--front-face", o.frontFace, "Front-face winding as seen on the image")
      ->check(CLI::IsMember({"ccw", "cw"}));
  app.add_option("--depth-compare", o.depthCompare, "Depth comparison")
      ->check(CLI::IsMember({"never", "less", "equal", "less-equal", "greater", "not-equal",
                             "greater-equal", "always"}));
  app.add_flag("--no-depth-write", o.noDepthWrite, "Leave the depth buffer unchanged");
  app.add_option("--threads", o.threads, "Worker threads (0: all); outputs are identical for any")
      ->check(CLI::Range(0, 1024));
  app.add_option("--coverage-kernel", o.coverageKernel,
                 "Coverage kernel: auto, scalar, or a SIMD target from --list-kernels; outputs are "
                 "identical for any");
  app.add_flag("--list-kernels", o.listKernels, "Print the coverage kernels this machine runs");
  app.add_option("--shading", o.shading,
                 "lambert, normals, depth, triangle-id or constant (default: lambert for meshes, "
                 "constant for triangle lists)");
  app.add_option("-o,--output", o.output, "Colour image (PNG)");
  app.add_option("--depth-output", o.depthOutput, "Depth image (32-bit float EXR)");
  app.add_option("--count-output", o.countOutput,
                 "Per-pixel count of written fragments (16-bit PNG or PGM)");
  app.add_option("--stats", o.statsOutput, "Pipeline statistics (JSON)");
  app.add_option("--eye", o.eye, "Camera position x y z")->expected(3);
  app.add_option("--target", o.target, "Point the camera looks at, x y z")->expected(3);
  app.add_option("--fov", o.fov, "Vertical field of view in degrees")->check(CLI::Range(1.0, 179.0));
  app.add_option("--near", o.nearPlane, "Near plane distance")->check(CLI::PositiveNumber);
  app.add_option("--far", o.farPlane, "Far plane distance")->check(CLI::PositiveNumber);
  for (CLI::Option* option : app.get_options()) option->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(e.what());
  }
  try {
    return run(o);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}
