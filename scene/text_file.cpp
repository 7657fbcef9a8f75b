#include "scene/text_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace rast {

Status readTextFile(const std::string& path, std::string& text) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Status::error(path + ": is a directory");
  std::ifstream file(path, std::ios::binary);
  if (!file) return Status::error(path + ": cannot open file");
  text.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  if (file.bad()) return Status::error(path + ": cannot read file");
  return Status::ok();
}

}  // namespace rast
