// Fuzzes the OBJ parser (scene/mesh.h parseObj): any text either loads into a mesh whose indices
// are in range, three per triangle, with finite positions and unit (or default) normals, or is
// refused with a one-line message naming the input.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "scene/mesh.h"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "obj_fuzzer: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rast::Mesh mesh;
  const rast::Status s = rast::parseObj(text, "fuzz.obj", mesh);
  if (!s) {
    if (!s.message().starts_with("fuzz.obj")) fail("the error does not name the input");
    if (s.message().find('\n') != std::string::npos) fail("the error is not one line");
    if (!mesh.vertices.empty() || !mesh.indices.empty()) fail("a refused file filled the mesh");
    return 0;
  }
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) fail("not whole triangles");
  for (const uint32_t i : mesh.indices)
    if (i >= mesh.vertices.size()) fail("an index out of range");
  for (const rast::MeshVertex& v : mesh.vertices) {
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(v.position[k]) || !std::isfinite(v.normal[k])) fail("non-finite vertex");
    const float len = std::sqrt(v.normal.x * v.normal.x + v.normal.y * v.normal.y +
                                v.normal.z * v.normal.z);
    if (std::abs(len - 1.0f) > 1e-4f) fail("a normal is not unit length");
  }
  return 0;
}
