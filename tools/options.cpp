#include "tools/options.h"

#include <cstdio>

#include <CLI/CLI.hpp>

namespace rast::tool {

int fail(const std::string& message) {
  std::fprintf(stderr, "rasterize: %s\n", message.c_str());
  return 1;
}

bool frameFileName(const std::string& pattern, int frame, std::string& out, std::string& error) {
  std::string result;
  int conversions = 0;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      result += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      result += '%';
      ++i;
      continue;
    }
    // %d or %0Nd with N in 1..9.
    size_t j = i + 1;
    int width = 0;
    if (j + 1 < pattern.size() && pattern[j] == '0' && pattern[j + 1] >= '1' && pattern[j + 1] <= '9') {
      width = pattern[j + 1] - '0';
      j += 2;
    }
    if (j >= pattern.size() || pattern[j] != 'd') {
      error = "--output-pattern '" + pattern + "': only %d, %0Nd (N 1..9) and %% may follow %";
      return false;
    }
    std::string number = std::to_string(frame);
    if (int(number.size()) < width) number.insert(0, size_t(width) - number.size(), '0');
    result += number;
    ++conversions;
    i = j;
  }
  if (conversions != 1) {
    error = "--output-pattern '" + pattern + "' needs exactly one %d or %0Nd for the frame number";
    return false;
  }
  out = result;
  return true;
}

std::optional<int> parseOptions(int argc, char** argv, Options& o) {
  for (int i = 0; i < argc; ++i) o.commandLine += (i ? " " : "") + std::string(argv[i]);
  CLI::App app{"Renders a scene with the tiled fixed-point rasterizer.\n"
               "With no input, renders the built-in default scene."};
  app.add_option("input", o.input,
                 "Scene file (.json), OBJ mesh (.obj) or window-space triangle list (any other name)");
  app.add_option("--input-kind", o.inputKind, "How to read the input")
      ->check(CLI::IsMember({"auto", "scene", "obj", "triangles"}));
  app.add_option("--scene", o.scene, "Scene file (JSON): cameras, lights, meshes, per-draw state");
  app.add_option("--width", o.width, "Image width in pixels (overrides a scene file's)")
      ->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "Image height in pixels (overrides a scene file's)")
      ->check(CLI::Range(1, 16384));
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
  app.add_option("--back-end", o.backEnd,
                 "Instruction set of the tile loop: auto (AVX2 where the CPU has it) or baseline "
                 "(x86-64 SSE2); outputs are identical for either")
      ->check(CLI::IsMember({"auto", "baseline"}));
  app.add_option("--bin-levels", o.binLevels,
                 "Binning of large triangles: coarse (per 64x64-pixel tile first) or tiles (tile by "
                 "tile); outputs and statistics are identical for either")
      ->check(CLI::IsMember({"coarse", "tiles"}));
  app.add_option("--defer-shading", o.deferShading,
                 "on: where a pixel keeps its last passing fragment's colour, a tile shades only "
                 "the fragments it keeps; off: every passing fragment as it passes; outputs and "
                 "statistics are identical for either")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--shading", o.shading,
                 "lambert, normals, depth, triangle-id, constant or blinn-phong (shadow-mapped) "
                 "(default: lambert for meshes, constant for triangle lists, the scene file's "
                 "shaders)");
  app.add_option("-o,--output", o.output, "Colour image (PNG); of the first frame of a sequence");
  app.add_option("--depth-output", o.depthOutput, "Depth image (32-bit float EXR)");
  app.add_option("--count-output", o.countOutput,
                 "Per-pixel count of written fragments (16-bit PNG or PGM)");
  app.add_option("--stats", o.statsOutput,
                 "Pipeline statistics (JSON): the frame's counters, derived counters, stage "
                 "times and the same per draw");
  app.add_flag("--print-stats", o.printStats,
               "Print the statistics per draw and per frame, and the time per stage, as a table");
  app.add_option("--eye", o.eye, "Camera position x y z")->expected(3);
  app.add_option("--target", o.target, "Point the camera looks at, x y z")->expected(3);
  app.add_option("--fov", o.fov, "Vertical field of view in degrees")->check(CLI::Range(1.0, 179.0));
  app.add_option("--near", o.nearPlane, "Near plane distance")->check(CLI::PositiveNumber);
  app.add_option("--far", o.farPlane, "Far plane distance")->check(CLI::PositiveNumber);
  app.add_option("--frames", o.frames,
                 "Frames of a sequence (needs --output-pattern): the scene's animation, or one "
                 "turn of the camera about its target")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--output-pattern", o.outputPattern,
                 "Render the sequence to numbered images, e.g. out/frame_%04d.png");
  app.add_option("--debug-images", o.debugImages,
                 "Folder for the debugging images of the (first) frame: bin and overdraw heat "
                 "maps, triangle ids, depth, the stage that decided each pixel, a tile's coverage");
  std::string tile;
  app.add_option("--tile", tile, "Tile X,Y to zoom into (default: the one with most bin entries)");
  app.add_option("--report", o.report, "Self-contained HTML report of the run");
  app.add_option("--precision-table", o.precisionTable,
                 "CSV table from the precision laboratory, shown in the report");
  for (CLI::Option* option : app.get_options()) option->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(e.what());
  }
  for (CLI::Option* option : app.get_options())
    if (option->count() > 0)
      for (const std::string& name : option->get_lnames()) o.given.insert("--" + name);
  if (!tile.empty()) {
    int x = 0, y = 0;
    char extra = 0;
    if (std::sscanf(tile.c_str(), "%d,%d%c", &x, &y, &extra) != 2 || x < 0 || y < 0)
      return fail("--tile '" + tile + "': expected X,Y (tile column and row, from 0)");
    o.tile = std::make_pair(x, y);
  }
  return std::nullopt;
}

}  // namespace rast::tool
