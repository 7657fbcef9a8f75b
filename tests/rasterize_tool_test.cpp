// The `rasterize` command-line tool, run as a subprocess (RASTERIZE_TOOL) the way a user runs it:
// good inputs give the right images and statistics; every bad input gives a non-zero exit status
// (a normal exit, never a signal) and exactly one line on stderr naming the problem.
// Each test works in its own temporary folder, removed afterwards.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "pipeline/framebuffer.h"
#include "scene/scene.h"

extern char** environ;

namespace rast {
namespace {

namespace fs = std::filesystem;

struct RunResult {
  bool exited = false;  // false: ended by a signal (a crash, an abort, a sanitizer trap)
  int exitCode = -1;
  int signal = 0;
  std::string out, err;
};

std::string readFile(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class RasterizeTool : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("rasterize_tool_test_" + std::string(info->name()) + "_" +
                                        std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path path(const std::string& name) const { return dir_ / name; }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }

  // Runs the tool with these arguments, no shell involved; stdout and stderr go to files.
  RunResult run(const std::vector<std::string>& args) const {
    std::vector<std::string> argv = {RASTERIZE_TOOL};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    const std::string outPath = path("stdout.txt"), errPath = path("stderr.txt");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    RunResult r;
    const int rc = posix_spawn(&pid, cargv[0], &actions, nullptr, cargv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    EXPECT_EQ(rc, 0) << "cannot start " << RASTERIZE_TOOL;
    if (rc != 0) return r;
    int status = 0;
    waitpid(pid, &status, 0);
    r.exited = WIFEXITED(status);
    r.exitCode = r.exited ? WEXITSTATUS(status) : -1;
    r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    r.out = readFile(outPath);
    r.err = readFile(errPath);
    return r;
  }

  // A bad input: a normal, non-zero exit, and one line on stderr, "rasterize: ..." containing
  // every one of `mentions` (the file, the line, the offending token or option).
  void expectOneLineError(const std::vector<std::string>& args,
                          const std::vector<std::string>& mentions) const {
    const RunResult r = run(args);
    EXPECT_TRUE(r.exited) << "killed by signal " << r.signal << "; stderr: " << r.err;
    EXPECT_NE(r.exitCode, 0);
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not exactly one line: " << r.err;
    EXPECT_EQ(r.err.rfind("rasterize: ", 0), 0u) << r.err;
    for (const std::string& m : mentions)
      EXPECT_NE(r.err.find(m), std::string::npos) << "'" << m << "' not in: " << r.err;
    EXPECT_FALSE(fs::exists(path("out.png"))) << "an image was written despite the error";
  }

  // Runs the tool once with `option` set to each of two values (and `args` besides), and expects
  // the same image bytes and the same values of the statistics named in `keys`. Returns the first
  // run's statistics.
  nlohmann::json expectSameImageAndCounters(const std::vector<std::string>& args,
                                            const std::string& option,
                                            const std::array<std::string, 2>& values,
                                            const std::vector<std::string>& keys) const {
    std::string images[2];
    nlohmann::json stats[2];
    for (int k = 0; k < 2; ++k) {
      const std::string image = path(values[k] + ".png").string();
      const std::string json = path(values[k] + ".json").string();
      std::vector<std::string> argv = args;
      argv.insert(argv.end(), {option, values[k], "-o", image, "--stats", json});
      const RunResult r = run(argv);
      EXPECT_TRUE(r.exited);
      EXPECT_EQ(r.exitCode, 0) << r.err;
      images[k] = readFile(image);
      if (r.exitCode != 0) return {};
      stats[k] = nlohmann::json::parse(readFile(json));
    }
    EXPECT_FALSE(images[0].empty());
    // (Not EXPECT_EQ: a failure would print both images' bytes.)
    EXPECT_TRUE(images[0] == images[1])
        << "the images differ with " << option << " " << values[0] << " and " << values[1];
    for (const std::string& key : keys) EXPECT_EQ(stats[0].at(key), stats[1].at(key)) << key;
    return stats[0];
  }

  fs::path dir_;
};

// Reads a one-channel image as 16-bit values.
std::vector<uint16_t> readGrey16(const fs::path& file, int& width, int& height) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  EXPECT_EQ(spec.nchannels, 1);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::UINT16);
  std::vector<uint16_t> pixels(size_t(width) * height * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT16, pixels.data()));
  return pixels;
}

// The default scene through the tool gives the same picture and counters as renderScene called
// in-process with the same settings (Lambert shading, 24.4, 160x120).
TEST_F(RasterizeTool, DefaultSceneMatchesInProcessRender) {
  const RunResult r = run({"--width", "160", "--height", "120", "-o", path("out.png").string(),
                           "--stats", path("stats.json").string()});
  ASSERT_TRUE(r.exited);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;

  Framebuffer fb(160, 120);
  PipelineState state;
  state.viewport = {0, 0, 160, 120};
  PipelineStatistics stats;
  ASSERT_TRUE(renderScene(defaultScene(), fb, state, ShadingMode::Lambert, stats));
  ASSERT_GT(stats.fragmentsWritten, 0u);

  const nlohmann::json json = nlohmann::json::parse(readFile(path("stats.json")));
  EXPECT_EQ(json.at("merge.fragments_written").get<uint64_t>(), stats.fragmentsWritten);
  EXPECT_EQ(json.at("clip.input_triangles").get<uint64_t>(), 3677u);  // 2 + 1 + 3,674 (bunny)
  EXPECT_EQ(json.at("setup.triangles").get<uint64_t>(), stats.setupTriangles);

  auto in = OIIO::ImageInput::open(path("out.png").string());
  ASSERT_TRUE(in);
  ASSERT_EQ(in->spec().width, 160);
  ASSERT_EQ(in->spec().height, 120);
  ASSERT_EQ(in->spec().nchannels, 4);
  std::vector<uint8_t> rgba(160 * 120 * 4);
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, rgba.data()));
  int different = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      const PackedColor c = fb.color(x, y);
      const uint8_t* p = &rgba[(size_t(y) * 160 + x) * 4];
      for (int k = 0; k < 4; ++k) different += p[k] != ((c >> (8 * k)) & 255);
    }
  EXPECT_EQ(different, 0);  // PNG is lossless: byte for byte
}

// Two triangles forming the 4x4-pixel square [2, 6] x [2, 6] of an 8x8 image. Pixel centres on
// the shared diagonal (x == y) are on both triangles' edge: the fill rule must give each of them
// to exactly one triangle, so the count image is 1 on exactly those 16 pixels and 0 elsewhere.
TEST_F(RasterizeTool, SquareCountsEachPixelOnce) {
  write("square.txt",
        "# a square from two triangles\n"
        "2 2 0.5  6 2 0.5  6 6 0.5\n"
        "\n"
        "2 2 0.5  6 6 0.5  2 6 0.5\n");
  const RunResult r = run({path("square.txt").string(), "--width", "8", "--height", "8",
                           "--count-output", path("count.png").string(), "--stats",
                           path("stats.json").string()});
  ASSERT_TRUE(r.exited);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int width = 0, height = 0;
  const std::vector<uint16_t> counts = readGrey16(path("count.png"), width, height);
  ASSERT_EQ(width, 8);
  ASSERT_EQ(height, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const int expected = (x >= 2 && x < 6 && y >= 2 && y < 6) ? 1 : 0;
      EXPECT_EQ(counts[size_t(y) * 8 + x], expected) << "pixel " << x << ", " << y;
    }
  const nlohmann::json json = nlohmann::json::parse(readFile(path("stats.json")));
  EXPECT_EQ(json.at("merge.fragments_written").get<uint64_t>(), 16u);
  EXPECT_EQ(json.at("clip.input_triangles").get<uint64_t>(), 2u);
}

// Overlap with the depth test off (--depth-compare always): the count image counts layers.
// Square A = [0, 4] x [0, 4], square B = [2, 6] x [2, 6]: 2 on [2, 4) x [2, 4), 1 on the rest
// of the union (16 + 16 - 4 = 28 pixels), 0 elsewhere.
TEST_F(RasterizeTool, OverlapCountsLayers) {
  write("two.txt",
        "0 0 0.5  4 0 0.5  4 4 0.5\n0 0 0.5  4 4 0.5  0 4 0.5\n"
        "2 2 0.25  6 2 0.25  6 6 0.25\n2 2 0.25  6 6 0.25  2 6 0.25\n");
  const RunResult r = run({path("two.txt").string(), "--width", "8", "--height", "8",
                           "--depth-compare", "always", "--count-output",
                           path("count.png").string()});
  ASSERT_TRUE(r.exited);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int width = 0, height = 0;
  const std::vector<uint16_t> counts = readGrey16(path("count.png"), width, height);
  ASSERT_EQ(counts.size(), 64u);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool inA = x < 4 && y < 4, inB = x >= 2 && x < 6 && y >= 2 && y < 6;
      EXPECT_EQ(counts[size_t(y) * 8 + x], int(inA) + int(inB)) << "pixel " << x << ", " << y;
    }
}

// 300 copies of one square (two triangles each): counts above 255 survive in the binary PGM
// count image (16-bit samples; the PNG path is read back as 16-bit in the tests above).
TEST_F(RasterizeTool, CountsAboveEightBitsSurviveInPgm) {
  std::string list;
  for (int i = 0; i < 300; ++i) list += "0 0 0.5  4 0 0.5  4 4 0.5\n0 0 0.5  4 4 0.5  0 4 0.5\n";
  write("stack.txt", list);
  const RunResult r = run({path("stack.txt").string(), "--width", "8", "--height", "8",
                           "--depth-compare", "always", "--count-output",
                           path("count.pgm").string()});
  ASSERT_TRUE(r.exited);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(readFile(path("count.pgm")).rfind("P5\n8 8\n65535\n", 0), 0u);
  int width = 0, height = 0;
  const std::vector<uint16_t> counts = readGrey16(path("count.pgm"), width, height);
  ASSERT_EQ(counts.size(), 64u);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(counts[size_t(y) * 8 + x], x < 4 && y < 4 ? 300 : 0) << "pixel " << x << ", " << y;
}

// (A missing OBJ takes loadObj's path: Mesh.LoadObjMissingFile. Every run of the tool costs
// ~0.4 s of dynamic loading, OpenImageIO's dependencies, so runs are not duplicated here.)
TEST_F(RasterizeTool, MissingFile) {
  expectOneLineError({path("nothing.txt").string(), "-o", path("out.png").string()},
                     {"nothing.txt", "cannot open"});
}

TEST_F(RasterizeTool, TriangleListWithSevenNumbers) {
  write("seven.txt", "0 0 0 4 0 0 4 4 0\n1 2 3 4 5 6 7\n");
  expectOneLineError({path("seven.txt").string(), "-o", path("out.png").string()},
                     {"seven.txt:2:", "expected 9 numbers", "found 7"});
}

TEST_F(RasterizeTool, TriangleListWithAWord) {
  write("word.txt", "0 0 0 4 0 zero 4 4 0\n");
  expectOneLineError({path("word.txt").string(), "-o", path("out.png").string()},
                     {"word.txt:1:", "'zero' is not a number"});
}

TEST_F(RasterizeTool, TriangleListWithNaN) {
  write("nan.txt", "# header\n0 0 0 4 0 nan 4 4 0\n");
  expectOneLineError({path("nan.txt").string(), "-o", path("out.png").string()},
                     {"nan.txt:2:", "non-finite"});
}

TEST_F(RasterizeTool, ObjOfGarbage) {
  write("garbage.obj", "This is not\nan OBJ file {}\n\x01\x02\x03\n");
  expectOneLineError({path("garbage.obj").string(), "-o", path("out.png").string()},
                     {"garbage.obj", "no triangles"});
}

TEST_F(RasterizeTool, ObjFaceIndexOutOfRange) {
  write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  expectOneLineError({path("range.obj").string(), "-o", path("out.png").string()},
                     {"range.obj", "vertex 4 of 3"});
}

TEST_F(RasterizeTool, ObjNonNumericCoordinate) {
  // tinyobjloader alone reads "abc" as 0 and draws the triangle (fixed in scene/mesh.cpp).
  write("word.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n");
  expectOneLineError({path("word.obj").string(), "-o", path("out.png").string()},
                     {"word.obj:2:", "'abc' is not a number"});
}

// --bin-levels changes neither the picture nor a counter: a quad over a 300x200 image (coarse
// entries for the tiles inside each half) under a smaller triangle, with either levels.
TEST_F(RasterizeTool, BinLevelsGiveTheSameImageAndCounters) {
  write("quad.txt",
        "0 0 0.5  300 0 0.5  300 200 0.5\n0 0 0.5  300 200 0.5  0 200 0.5\n"
        "20 30 0.25  170 60 0.25  90 180 0.25\n");
  const nlohmann::json stats = expectSameImageAndCounters(
      {path("quad.txt").string(), "--width", "300", "--height", "200"}, "--bin-levels",
      {"coarse", "tiles"},
      {"bin.entries", "bin.tiles_trivially_rejected", "raster.tiles_trivially_accepted",
       "merge.fragments_written"});
  ASSERT_FALSE(stats.empty());
  EXPECT_GT(stats.at("merge.fragments_written").get<uint64_t>(), 300u * 200u);  // the quad, then the triangle
}

// A lit mesh drawn with overdraw (no culling): the same image and counters whether tiles shade
// only the fragments they keep or every passing one.
TEST_F(RasterizeTool, DeferredShadingGivesTheSameImageAndCounters) {
  const nlohmann::json stats = expectSameImageAndCounters(
      {std::string(RASTER_SHARED_MESHES) + "/bunny.obj", "--width", "320", "--height", "240",
       "--cull", "none", "--shading", "lambert"},
      "--defer-shading", {"on", "off"},
      {"pixel.shader_invocations", "merge.depth_passed", "merge.fragments_written"});
  ASSERT_FALSE(stats.empty());
  EXPECT_GT(stats.at("pixel.shader_invocations").get<uint64_t>(), 10000u);
}

TEST_F(RasterizeTool, UnknownOption) {
  expectOneLineError({"--frobnicate", "-o", path("out.png").string()}, {"--frobnicate"});
}

TEST_F(RasterizeTool, BadOptionValues) {
  expectOneLineError({"--subpixel-bits", "9", "-o", path("out.png").string()},
                     {"--subpixel-bits", "9"});
  expectOneLineError({"--width", "0", "-o", path("out.png").string()}, {"--width", "0"});
  expectOneLineError({"--bin-levels", "three", "-o", path("out.png").string()},
                     {"--bin-levels", "three"});
}

TEST_F(RasterizeTool, UnwritableOutput) {
  const std::string out = path("no/such/folder/out.png").string();
  expectOneLineError({"--width", "16", "--height", "16", "-o", out}, {"cannot write", out});
  const std::string stats = path("no/such/folder/stats.json").string();
  expectOneLineError({"--width", "16", "--height", "16", "--stats", stats},
                     {"cannot write", stats});
}

}  // namespace
}  // namespace rast
