// The rasterize tool's command line: every option, its checks and its help text.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace rast::tool {

struct Options {
  std::string input;  // empty: the built-in default scene (or --scene)
  std::string inputKind = "auto";
  std::string scene;  // --scene: a scene file (JSON)
  int width = 960, height = 540;
  int subpixelBits = 4;
  std::string cull = "none", frontFace = "ccw", depthCompare = "less", shading;
  bool noDepthWrite = false;
  int threads = 0;
  std::string coverageKernel = "auto";
  std::string backEnd = "auto";
  std::string binLevels = "coarse";
  std::string deferShading = "on";
  bool listKernels = false;
  std::string output, depthOutput, countOutput, statsOutput;
  std::vector<float> eye, target;
  float fov = 45.0f, nearPlane = 0.0f, farPlane = 0.0f;
  // Sequences.
  int frames = 0;  // 0: the scene's animation, if any
  std::string outputPattern;
  // Looking inside.
  bool printStats = false;
  std::string debugImages;  // folder
  std::optional<std::pair<int, int>> tile;
  std::string report, precisionTable;

  std::string commandLine;    // as typed, for the report
  std::set<std::string> given;  // long names of the options given on the command line

  bool has(const std::string& name) const { return given.count(name) > 0; }
};

// Parses the command line. Returns an exit status when the program should stop (after --help,
// or with a one-line error already printed), nothing when it should run.
std::optional<int> parseOptions(int argc, char** argv, Options& out);

// "rasterize: message" on stderr; returns 1.
int fail(const std::string& message);

// The file name of frame `frame` from a pattern holding one printf-style %d or %0Nd (and %% for
// a percent sign). Fails with a message naming the pattern otherwise.
bool frameFileName(const std::string& pattern, int frame, std::string& out, std::string& error);

}  // namespace rast::tool
