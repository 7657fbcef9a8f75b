// rasterize: renders the built-in default scene, a scene file, an OBJ mesh or a window-space
// triangle list to images (colour, depth, per-pixel fragment count) or to a numbered image
// sequence; writes and prints the pipeline statistics per draw and per frame; draws debugging
// images and an HTML report of the run.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <glm/geometric.hpp>

#include "debug/debug_images.h"
#include "debug/report.h"
#include "debug/statistics_table.h"
#include "scene/frame.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "scene/triangle_list.h"
#include "tools/options.h"

namespace {

using namespace rast;
using namespace rast::tool;

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

// What is rendered: a scene (built-in, OBJ or file) seen by a camera per frame, or a triangle list.
struct Source {
  std::string name;  // for messages and the report
  std::string kind;  // "default", "scene", "obj" or "triangles"
  SceneDescription scene;
  std::vector<WindowVertex> triangles;
  PipelineState triangleState;
  ShadingMode triangleShading = ShadingMode::Constant;
  std::optional<CameraAnimation> animation;
  // Blinn-Phong with a shadow map needs a light pass before the camera pass, which frame plans
  // do not describe: such a scene (built-in or OBJ) is rendered by renderScene, one frame.
  std::optional<Scene> shadowed;

  FramePlan plan(int frame) const {
    if (kind == "triangles")
      return planTriangleList(triangles, triangleState, triangleShading, scene.width, scene.height);
    const Camera camera = animation ? cameraAtFrame(scene.camera, *animation, frame) : scene.camera;
    return planFrame(scene, camera);
  }
};

PipelineState stateFromOptions(const Options& o) {
  PipelineState state;
  state.viewport = {0, 0, o.width, o.height};
  state.format = FixedPointFormat::withFractionBits(o.subpixelBits);
  state.cullMode = kCullModes.at(o.cull);
  state.frontFace = kFrontFaces.at(o.frontFace);
  state.depth.compare = kCompareOps.at(o.depthCompare);
  state.depth.write = !o.noDepthWrite;
  return state;
}

// The state options given on the command line, applied to every draw of a scene file.
void overrideState(const Options& o, PipelineState& s) {
  if (o.has("--subpixel-bits")) s.format = FixedPointFormat::withFractionBits(o.subpixelBits);
  if (o.has("--cull")) s.cullMode = kCullModes.at(o.cull);
  if (o.has("--front-face")) s.frontFace = kFrontFaces.at(o.frontFace);
  if (o.has("--depth-compare")) s.depth.compare = kCompareOps.at(o.depthCompare);
  if (o.has("--no-depth-write")) s.depth.write = false;
}

Status loadSource(const Options& o, Source& src) {
  std::string kind = o.inputKind;
  if (!o.scene.empty()) {
    if (!o.input.empty()) return Status::error("give either an input or --scene, not both");
    kind = "scene";
  } else if (kind == "auto") {
    kind = o.input.empty() ? "default"
           : endsWith(o.input, ".json") ? "scene"
           : endsWith(o.input, ".obj")  ? "obj"
                                        : "triangles";
  }
  src.kind = kind;
  const std::string path = o.scene.empty() ? o.input : o.scene;
  src.name = kind == "default" ? "default scene" : path;
  ShadingMode shading = ShadingMode::Lambert;
  if (!o.shading.empty() && !parseShadingMode(o.shading, shading))
    return Status::error("unknown shading '" + o.shading + "'");

  if (kind == "triangles") {
    if (Status s = loadTriangleList(path, src.triangles); !s) return s;
    src.triangleState = stateFromOptions(o);
    src.triangleState.positionSpace = PositionSpace::Window;
    const std::string name = o.shading.empty() ? "constant" : o.shading;
    if (name != "constant" && name != "triangle-id" && name != "depth")
      return Status::error("shading '" + name +
                           "' needs normals; triangle lists take constant, triangle-id or depth");
    parseShadingMode(name, src.triangleShading);
    src.scene.width = o.width;
    src.scene.height = o.height;
    return Status::ok();
  }

  if (kind == "scene") {
    if (Status s = loadSceneFile(path, src.scene); !s) return s;
    if (o.has("--width")) src.scene.width = o.width;
    if (o.has("--height")) src.scene.height = o.height;
    if (shading == ShadingMode::BlinnPhong)
      return Status::error("shading blinn-phong is for the built-in scene and OBJ meshes, not scene "
                           "files");
    for (DrawSpec& d : src.scene.draws) {
      overrideState(o, d.state);
      if (!o.shading.empty()) d.shader.kind = shading;
      if (d.shader.kind == ShadingMode::Lambert && size_t(d.shader.light) >= src.scene.lights.size())
        return Status::error(path + ": shading lambert needs a light, and the scene has none");
    }
    if (o.has("--fov")) src.scene.camera.fovYDegrees = o.fov;
  } else {
    Scene scene;
    if (kind == "default") {
      scene = defaultScene();
    } else {
      SceneObject object;
      if (Status s = loadObj(path, object.mesh); !s) return s;
      scene.camera = frameMesh(object.mesh, o.fov);
      scene.lightPosition = scene.camera.eye + glm::vec3(0.35f, 0.55f, 0.76f) *
                                                   glm::distance(scene.camera.eye, scene.camera.target);
      scene.background = {0.1f, 0.1f, 0.12f, 1.0f};
      scene.objects.push_back(std::move(object));
    }
    scene.camera.fovYDegrees = o.fov;
    if (shading == ShadingMode::BlinnPhong) src.shadowed = scene;
    src.scene = describeScene(scene, stateFromOptions(o),
                              shading == ShadingMode::BlinnPhong ? ShadingMode::Lambert : shading);
  }
  Camera& camera = src.scene.camera;
  if (!o.eye.empty()) camera.eye = {o.eye[0], o.eye[1], o.eye[2]};
  if (!o.target.empty()) camera.target = {o.target[0], o.target[1], o.target[2]};
  if (o.nearPlane > 0) camera.nearPlane = o.nearPlane;
  if (o.farPlane > 0) camera.farPlane = o.farPlane;
  if (!(camera.nearPlane < camera.farPlane)) return Status::error("--near must be smaller than --far");
  return Status::ok();
}

// The frames to render: the scene's animation, --frames of it, or without one a turn of the
// camera about its target.
Status chooseAnimation(const Options& o, Source& src, int& frames) {
  frames = 1;
  if (o.outputPattern.empty()) {
    if (o.has("--frames")) return Status::error("--frames needs --output-pattern");
    return Status::ok();  // a single image: the first frame of any animation
  }
  if (src.kind == "triangles") return Status::error("a triangle list has no camera to animate");
  src.animation = src.scene.animation;
  if (!src.animation) {
    if (!o.has("--frames"))
      return Status::error("--output-pattern needs --frames N, or a scene with an \"animation\"");
    CameraAnimation turn;
    turn.frames = o.frames;
    turn.motion = OrbitAnimation{src.scene.camera.target, src.scene.camera.up, 360.0f};
    src.animation = turn;
  }
  if (o.has("--frames")) src.animation->frames = o.frames;
  frames = src.animation->frames;
  return Status::ok();
}

// A progress bar on stderr, drawn only on a terminal (never into CI logs).
class Progress {
 public:
  explicit Progress(int total) : total_(total), enabled_(total > 1 && isatty(STDERR_FILENO)) {}
  void update(int done) const {
    if (!enabled_) return;
    constexpr int kWidth = 30;
    const int filled = done * kWidth / total_;
    std::fprintf(stderr, "\r[%s%s] %d/%d frames", std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(kWidth - filled), ' ').c_str(), done, total_);
    if (done == total_) std::fputc('\n', stderr);
    std::fflush(stderr);
  }

 private:
  int total_;
  bool enabled_;
};

Status writeText(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (!f || !(f << text)) return Status::error("cannot write '" + path + "'");
  return Status::ok();
}

TableData sceneTable(const Source& src, int frames) {
  auto vec = [](glm::vec3 v) {
    char b[96];
    std::snprintf(b, sizeof b, "%g, %g, %g", v.x, v.y, v.z);
    return std::string(b);
  };
  TableData t;
  t.header = {"property", "value"};
  t.rows.push_back({"source", src.name});
  if (!src.scene.description.empty()) t.rows.push_back({"description", src.scene.description});
  t.rows.push_back({"image", std::to_string(src.scene.width) + " x " + std::to_string(src.scene.height)});
  t.rows.push_back({"frames", std::to_string(frames)});
  if (src.kind != "triangles") {
    const Camera& c = src.scene.camera;
    t.rows.push_back({"camera eye", vec(c.eye)});
    t.rows.push_back({"camera target", vec(c.target)});
    t.rows.push_back({"field of view, near, far", std::to_string(c.fovYDegrees) + ", " +
                                                      std::to_string(c.nearPlane) + ", " +
                                                      std::to_string(c.farPlane)});
    for (size_t i = 0; i < src.scene.lights.size(); ++i)
      t.rows.push_back({"light " + std::to_string(i), vec(src.scene.lights[i].position)});
  } else {
    t.rows.push_back({"triangles", std::to_string(src.triangles.size() / 3)});
  }
  return t;
}

RgbImage colorImage(const Framebuffer& fb) {
  RgbImage img(fb.width(), fb.height());
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    const PackedColor c = fb.colorPlane()[i];
    img.pixels[i] = {uint8_t(c & 255), uint8_t((c >> 8) & 255), uint8_t((c >> 16) & 255)};
  }
  return img;
}

// Debugging images and the report, both of the first frame.
Status lookInside(const Options& o, const Source& src, const FramePlan& plan,
                  const Framebuffer& firstFrame, const FrameRecord& record, int frames,
                  const ExecutionOptions& exec) {
  DebugData data;
  if (Status s = captureDebugData(plan, o.tile, exec, data); !s) return s;
  const std::vector<DebugImage> images = debugImages(data);
  if (!o.debugImages.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.debugImages, ec);
    if (ec) return Status::error("cannot create folder '" + o.debugImages + "': " + ec.message());
    for (const DebugImage& image : images) {
      const std::string file = (std::filesystem::path(o.debugImages) / (image.name + ".png")).string();
      if (Status s = writePng(image.image, file); !s) return s;
    }
  }
  if (o.report.empty()) return Status::ok();
  ReportInput in;
  in.title = "rasterize: " + src.name;
  in.commandLine = o.commandLine;
  in.scene = sceneTable(src, frames);
  in.drawStates = drawStateTable(plan);
  in.statistics = statisticsTableData(record, false);
  in.timings = timingsTableData(record);
  in.images.push_back({"Render", "The colour image" + std::string(frames > 1 ? " of the first frame." : "."),
                       colorImage(firstFrame)});
  for (const DebugImage& image : images) in.images.push_back({image.title, image.caption, image.image});
  in.tileTriangles = tileTriangleTable(data);
  if (!o.precisionTable.empty()) {
    TableData precision;
    if (Status s = readCsvTable(o.precisionTable, precision); !s) return s;
    in.precision = std::move(precision);
    in.precisionSource = o.precisionTable;
  }
  std::string html;
  if (Status s = htmlReport(in, html); !s) return s;
  return writeText(o.report, html);
}

int run(const Options& o) {
  if (o.listKernels) {
    for (const CoverageKernel& k : availableCoverageKernels()) std::printf("%s\n", k.name.c_str());
    return 0;
  }
  ScratchMemory memory;  // kept across the frames of an animation or a frame plan
  ExecutionOptions exec;
  exec.threads = o.threads;
  exec.memory = &memory;
  exec.backEnd = o.backEnd == "baseline" ? BackEndTarget::Baseline : BackEndTarget::Auto;
  exec.binLevels = o.binLevels == "tiles" ? BinLevels::TilesOnly : BinLevels::Coarse;
  exec.deferShading = o.deferShading == "on";
  if (!findCoverageKernel(o.coverageKernel, exec.coverage))
    return fail("coverage kernel '" + o.coverageKernel +
                "' is not available on this machine (see --list-kernels)");
  if (o.tile && o.debugImages.empty() && o.report.empty())
    return fail("--tile needs --debug-images or --report");
  if (!o.precisionTable.empty() && o.report.empty()) return fail("--precision-table needs --report");

  Source src;
  if (Status s = loadSource(o, src); !s) return fail(s.message());
  int frames = 1;
  if (Status s = chooseAnimation(o, src, frames); !s) return fail(s.message());
  std::string firstName, error;
  if (!o.outputPattern.empty() && !frameFileName(o.outputPattern, 0, firstName, error)) return fail(error);

  const bool counts = !o.countOutput.empty();
  Framebuffer fb(src.scene.width, src.scene.height, counts, src.scene.samples);
  if (src.shadowed) {
    if (frames > 1 || !o.debugImages.empty() || !o.report.empty())
      return fail("shading blinn-phong renders one image: no sequences, debug images or report");
    Scene scene = *src.shadowed;
    scene.camera = src.scene.camera;
    PipelineState state = stateFromOptions(o);
    state.viewport = {0, 0, fb.width(), fb.height()};
    PipelineStatistics stats;
    if (Status s = renderScene(scene, fb, state, ShadingMode::BlinnPhong, stats, exec); !s)
      return fail(s.message());
    if (!o.output.empty())
      if (Status s = writeColorImage(fb, o.output); !s) return fail(s.message());
    if (!o.depthOutput.empty())
      if (Status s = writeDepthImage(fb, o.depthOutput); !s) return fail(s.message());
    if (counts)
      if (Status s = writeCountImage(fb, o.countOutput); !s) return fail(s.message());
    if (!o.statsOutput.empty())
      if (Status s = writeText(o.statsOutput, stats.toJson() + "\n"); !s) return fail(s.message());
    std::printf("%s: %llu triangles in, %llu set up, %llu fragments written (blinn-phong, %dx%d)\n",
                src.name.c_str(), (unsigned long long)stats.inputTriangles,
                (unsigned long long)stats.setupTriangles,
                (unsigned long long)stats.fragmentsWritten, fb.width(), fb.height());
    return 0;
  }
  std::optional<Framebuffer> firstFrame;
  FrameRecord record;
  std::vector<FrameRecord> perFrame;
  const Progress progress(frames);
  for (int f = 0; f < frames; ++f) {
    const FramePlan plan = src.plan(f);
    FrameRecord frame;
    if (Status s = renderFrame(plan, fb, frame, exec); !s) return fail(s.message());
    record.add(frame);
    if (frames > 1) perFrame.push_back(frame);
    if (f == 0) firstFrame = fb;
    if (!o.outputPattern.empty()) {
      std::string name;
      frameFileName(o.outputPattern, f, name, error);
      if (Status s = writeColorImage(fb, name); !s) return fail(s.message());
    }
    progress.update(f + 1);
  }

  if (!o.output.empty())
    if (Status s = writeColorImage(*firstFrame, o.output); !s) return fail(s.message());
  if (!o.depthOutput.empty())
    if (Status s = writeDepthImage(*firstFrame, o.depthOutput); !s) return fail(s.message());
  if (counts)
    if (Status s = writeCountImage(*firstFrame, o.countOutput); !s) return fail(s.message());
  if (!o.statsOutput.empty()) {
    nlohmann::ordered_json j = statisticsJson(record);
    if (frames > 1) {
      j["per_frame"] = nlohmann::ordered_json::array();
      for (const FrameRecord& f : perFrame) {
        nlohmann::ordered_json one = statisticsJson(f);
        one.erase("draws");
        j["per_frame"].push_back(std::move(one));
      }
    }
    if (Status s = writeText(o.statsOutput, j.dump(2) + "\n"); !s) return fail(s.message());
  }
  if (!o.debugImages.empty() || !o.report.empty())
    if (Status s = lookInside(o, src, src.plan(0), *firstFrame, record, frames, exec); !s)
      return fail(s.message());

  if (o.printStats) std::printf("%s\n", statisticsTable(record).c_str());
  const FixedPointFormat format =
      src.kind == "triangles" ? src.triangleState.format
                              : (src.scene.draws.empty() ? FixedPointFormat::d24_4()
                                                         : src.scene.draws.front().state.format);
  std::printf("%s: %llu triangles in, %llu set up, %llu fragments written (%s, %dx%d%s)\n",
              src.name.c_str(), (unsigned long long)record.total.inputTriangles,
              (unsigned long long)record.total.setupTriangles,
              (unsigned long long)record.total.fragmentsWritten, format.name().c_str(),
              src.scene.width, src.scene.height,
              frames > 1 ? (", " + std::to_string(frames) + " frames").c_str() : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (std::optional<int> exit = parseOptions(argc, argv, o)) return *exit;
  try {
    return run(o);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}
