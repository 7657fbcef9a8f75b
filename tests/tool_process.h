// Runs the rasterize tool (or any program) as a subprocess, no shell involved, in a temporary
// folder of the test's own that is removed afterwards.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

extern char** environ;

namespace rast::testing_tools {

namespace fs = std::filesystem;

struct ProcessResult {
  bool exited = false;
  int exitCode = -1;
  std::string out, err;
};

inline std::string readWholeFile(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class TempFolder {
 public:
  TempFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / (std::string(info->test_suite_name()) + "_" + info->name() +
                                        "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path operator/(const std::string& name) const { return dir_ / name; }
  const fs::path& path() const { return dir_; }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }

 private:
  fs::path dir_;
};

// `program` with `args`; stdout and stderr captured through files in `folder`.
inline ProcessResult runProcess(const std::string& program, const std::vector<std::string>& args,
                                const TempFolder& folder) {
  std::vector<std::string> argv = {program};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargv;
  for (std::string& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const std::string outPath = folder / "stdout.txt", errPath = folder / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid;
  ProcessResult r;
  const int rc = posix_spawnp(&pid, cargv[0], &actions, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return r;
  int status = 0;
  waitpid(pid, &status, 0);
  r.exited = WIFEXITED(status);
  r.exitCode = r.exited ? WEXITSTATUS(status) : -1;
  r.out = readWholeFile(outPath);
  r.err = readWholeFile(errPath);
  return r;
}

inline ProcessResult runTool(const std::vector<std::string>& args, const TempFolder& folder) {
  return runProcess(RASTERIZE_TOOL, args, folder);
}

// A bad input: a normal exit with status 1 and exactly one line "rasterize: ..." holding every
// one of `mentions`.
inline void expectToolError(const std::vector<std::string>& args, const std::vector<std::string>& mentions,
                            const TempFolder& folder) {
  const ProcessResult r = runTool(args, folder);
  EXPECT_TRUE(r.exited);
  EXPECT_EQ(r.exitCode, 1) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not exactly one line: " << r.err;
  EXPECT_EQ(r.err.rfind("rasterize: ", 0), 0u) << r.err;
  for (const std::string& m : mentions)
    EXPECT_NE(r.err.find(m), std::string::npos) << "'" << m << "' not in: " << r.err;
}

}  // namespace rast::testing_tools
