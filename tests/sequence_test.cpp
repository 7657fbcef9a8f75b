// The rasterize tool on scene files: image sequences (frame count and file names), statistics per
// draw and per frame, debugging images, and one-line errors for every bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "tool_process.h"

namespace rast {
namespace {

namespace fs = std::filesystem;
using testing_tools::expectToolError;
using testing_tools::readWholeFile;
using testing_tools::runTool;
using testing_tools::TempFolder;

const std::string kScene = R"({
  "width": 48, "height": 32,
  "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "near": 1, "far": 20},
  "lights": [{"position": [0, 5, 5]}],
  "meshes": {"quad": {"positions": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
                      "triangles": [[0, 1, 2], [0, 2, 3]]}},
  "draws": [{"label": "left", "mesh": "quad", "transform": {"translate": [-0.8, 0, 0]}, "shader": "lambert"},
            {"label": "right", "mesh": "quad", "transform": {"translate": [0.8, 0, -1]},
             "state": {"cull": "back"}, "shader": {"name": "constant", "color": [1, 0, 0]}}],
  "animation": {"frames": 3, "orbit": {"centre": [0, 0, 0], "axis": [0, 1, 0], "degrees": 90}}
})";

std::set<std::string> filesIn(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

std::vector<unsigned char> readPixels(const fs::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) return {};
  std::vector<unsigned char> pixels(size_t(in->spec().image_pixels()) * size_t(in->spec().nchannels));
  in->read_image(0, 0, 0, -1, OIIO::TypeDesc::UINT8, pixels.data());
  return pixels;
}

TEST(Sequence, RendersTheScenesFramesToNumberedImages) {
  TempFolder dir;
  const fs::path scene = dir.write("scene.json", kScene);
  fs::create_directories(dir / "frames");
  const auto r = runTool({scene.string(), "--output-pattern", (dir / "frames/f_%04d.png").string(),
                          "--stats", (dir / "stats.json").string()},
                         dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "no progress bar when stderr is not a terminal: " << r.err;
  EXPECT_EQ(filesIn(dir / "frames"), (std::set<std::string>{"f_0000.png", "f_0001.png", "f_0002.png"}));
  // The camera moves: every frame differs from the others.
  const auto f0 = readPixels(dir / "frames/f_0000.png"), f1 = readPixels(dir / "frames/f_0001.png"),
             f2 = readPixels(dir / "frames/f_0002.png");
  ASSERT_EQ(f0.size(), size_t(48 * 32 * 4));
  EXPECT_NE(f0, f1);
  EXPECT_NE(f1, f2);
  // Statistics: the run's sums at the top, per draw and per frame below, consistent.
  const nlohmann::json j = nlohmann::json::parse(readWholeFile(dir / "stats.json"));
  EXPECT_EQ(j.at("frames").get<int>(), 3);
  EXPECT_EQ(j.at("clip.input_triangles").get<uint64_t>(), 12u);  // 2 draws x 2 triangles x 3 frames
  ASSERT_EQ(j.at("per_frame").size(), 3u);
  ASSERT_EQ(j.at("draws").size(), 2u);
  EXPECT_EQ(j["draws"][0]["label"], "left");
  for (const char* counter : {"raster.samples_covered", "merge.fragments_written", "setup.culled_back"}) {
    uint64_t byFrame = 0, byDraw = 0;
    for (const auto& f : j["per_frame"]) byFrame += f[counter].get<uint64_t>();
    for (const auto& d : j["draws"]) byDraw += d["counters"][counter].get<uint64_t>();
    EXPECT_EQ(byFrame, j[counter].get<uint64_t>()) << counter;
    EXPECT_EQ(byDraw, j[counter].get<uint64_t>()) << counter;
  }
  EXPECT_GT(j.at("timings_ms").at("total").get<double>(), 0.0);
}

TEST(Sequence, FramesOptionOverridesOrOrbitsAScene) {
  TempFolder dir;
  const fs::path scene = dir.write("scene.json", kScene);
  fs::create_directories(dir / "a");
  ASSERT_EQ(runTool({"--scene", scene.string(), "--frames", "2", "--output-pattern",
                     (dir / "a/%d.png").string()}, dir).exitCode, 0);
  EXPECT_EQ(filesIn(dir / "a"), (std::set<std::string>{"0.png", "1.png"}));
  // The built-in scene has no animation: --frames turns the camera about its target.
  fs::create_directories(dir / "b");
  const auto r = runTool({"--width", "32", "--height", "24", "--frames", "4", "--output-pattern",
                          (dir / "b/frame_%03d.png").string(), "-o", (dir / "first.png").string()}, dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(filesIn(dir / "b"),
            (std::set<std::string>{"frame_000.png", "frame_001.png", "frame_002.png", "frame_003.png"}));
  EXPECT_EQ(readPixels(dir / "first.png"), readPixels(dir / "b/frame_000.png"));
  EXPECT_NE(readPixels(dir / "b/frame_000.png"), readPixels(dir / "b/frame_001.png"));
  EXPECT_NE(r.out.find("4 frames"), std::string::npos) << r.out;
}

TEST(Sequence, PrintsStatisticsAndWritesDebugImages) {
  TempFolder dir;
  const fs::path scene = dir.write("scene.json", kScene);
  const auto r = runTool({scene.string(), "--print-stats", "--debug-images", (dir / "dbg").string(),
                          "--tile", "1,1"}, dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out.rfind("counter ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("left"), std::string::npos);
  EXPECT_NE(r.out.find("right"), std::string::npos);
  EXPECT_NE(r.out.find("setup.triangles"), std::string::npos);
  EXPECT_NE(r.out.find("back_end"), std::string::npos);
  EXPECT_EQ(filesIn(dir / "dbg"),
            (std::set<std::string>{"bin_heatmap.png", "overdraw.png", "triangle_id.png", "depth.png",
                                   "stage.png", "tile_1_1.png"}));
}

TEST(Sequence, BadInputsGetOneLineErrors) {
  TempFolder dir;
  const fs::path scene = dir.write("scene.json", kScene);
  std::string badCull = kScene;
  badCull.replace(badCull.find(R"("cull": "back")"), 14, R"("cull": "bak")");
  const fs::path bad = dir.write("bad.json", badCull);
  const std::string pattern = (dir / "f_%d.png").string();
  expectToolError({bad.string()}, {bad.string(), "/draws/1/state/cull", "expected one of"}, dir);
  expectToolError({"--scene", (dir / "none.json").string()}, {"none.json: cannot open file"}, dir);
  expectToolError({"--scene", scene.string(), scene.string()}, {"either an input or --scene"}, dir);
  expectToolError({scene.string(), "--frames", "3"}, {"--frames needs --output-pattern"}, dir);
  expectToolError({scene.string(), "--output-pattern", (dir / "f.png").string()},
                  {"needs exactly one %d"}, dir);
  expectToolError({scene.string(), "--output-pattern", (dir / "f_%d_%d.png").string()},
                  {"needs exactly one %d"}, dir);
  expectToolError({scene.string(), "--output-pattern", (dir / "f_%s.png").string()},
                  {"only %d, %0Nd"}, dir);
  expectToolError({"--width", "16", "--height", "16", "--output-pattern", pattern},
                  {"--output-pattern needs --frames N"}, dir);
  expectToolError({scene.string(), "--debug-images", (dir / "d").string(), "--tile", "1;1"},
                  {"--tile '1;1'"}, dir);
  expectToolError({scene.string(), "--debug-images", (dir / "d").string(), "--tile", "6,0"},
                  {"tile 6,0 is outside the 6x4 tiles"}, dir);
  expectToolError({scene.string(), "--tile", "0,0"}, {"--tile needs --debug-images or --report"}, dir);
  expectToolError({scene.string(), "--report", (dir / "r.html").string(), "--precision-table",
                   (dir / "none.csv").string()},
                  {"none.csv: cannot open file"}, dir);
  expectToolError({scene.string(), "--precision-table", (dir / "p.csv").string()},
                  {"--precision-table needs --report"}, dir);
  EXPECT_FALSE(fs::exists(dir / "r.html"));
  EXPECT_FALSE(fs::exists(dir / "f_0.png"));
}

}  // namespace
}  // namespace rast
