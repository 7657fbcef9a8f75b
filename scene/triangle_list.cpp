#include "scene/triangle_list.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace rast {

Status parseTriangleList(std::string_view text, const std::string& name,
                         std::vector<WindowVertex>& out) {
  std::vector<WindowVertex> result;
  size_t lineNumber = 0;
  while (!text.empty()) {
    const size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    ++lineNumber;
    const std::string where = name + ":" + std::to_string(lineNumber) + ": ";

    float values[9];
    int count = 0;
    size_t pos = 0;
    while (true) {
      while (pos < line.size() && (line[pos] == ' ' || line[pos] == '\t' || line[pos] == '\r'))
        ++pos;
      if (pos == line.size() || (count == 0 && line[pos] == '#')) break;
      if (count == 9) return Status::error(where + "more than 9 numbers");
      float v;
      // Parsed straight to float, as a GPU API would receive the vertex.
      const auto [next, ec] = std::from_chars(line.data() + pos, line.data() + line.size(), v);
      if (ec == std::errc::result_out_of_range) {
        // A number, but beyond float (1e39; also underflow such as 1e-50, which from_chars
        // reports alike): say so rather than call it "not a number".
        size_t stop = pos;
        while (stop < line.size() && line[stop] != ' ' && line[stop] != '\t') ++stop;
        return Status::error(where + "'" + std::string(line.substr(pos, stop - pos)) +
                             "' is out of the float range");
      }
      if (ec != std::errc() || (next != line.data() + line.size() && *next != ' ' &&
                                *next != '\t' && *next != '\r')) {
        size_t stop = pos;
        while (stop < line.size() && line[stop] != ' ' && line[stop] != '\t') ++stop;
        return Status::error(where + "'" + std::string(line.substr(pos, stop - pos)) +
                             "' is not a number");
      }
      if (!std::isfinite(v)) return Status::error(where + "non-finite coordinate");
      values[count++] = v;
      pos = size_t(next - line.data());
    }
    if (count == 0) continue;
    if (count != 9)
      return Status::error(where + "expected 9 numbers (x y z for 3 vertices), found " +
                           std::to_string(count));
    for (int k = 0; k < 3; ++k)
      result.push_back({{values[3 * k], values[3 * k + 1], values[3 * k + 2]}});
  }
  if (result.empty()) return Status::error(name + ": no triangles");
  out = std::move(result);
  return Status::ok();
}

Status loadTriangleList(const std::string& path, std::vector<WindowVertex>& out) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return Status::error(path + ": cannot open file");
  std::stringstream buffer;
  buffer << file.rdbuf();
  return parseTriangleList(buffer.str(), path, out);
}

}  // namespace rast
