// Fuzzes the window-space triangle list parser (scene/triangle_list.h): any text either gives
// whole triangles of finite coordinates or a one-line error naming the input.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "scene/triangle_list.h"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "triangle_list_fuzzer: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<rast::WindowVertex> vertices;
  const rast::Status s = rast::parseTriangleList(text, "fuzz.txt", vertices);
  if (!s) {
    if (!s.message().starts_with("fuzz.txt")) fail("the error does not name the input");
    if (s.message().find('\n') != std::string::npos) fail("the error is not one line");
    return 0;
  }
  if (vertices.size() % 3 != 0) fail("not whole triangles");
  for (const rast::WindowVertex& v : vertices)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(v.position[k])) fail("a non-finite coordinate was accepted");
  return 0;
}
