#include "scene/mesh.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <tiny_obj_loader.h>

namespace rast {

extern const std::string_view kEmbeddedBunnyLowresObj;

namespace {

Status fromReader(const tinyobj::ObjReader& reader, bool ok, const std::string& name, Mesh& out) {
  if (!ok) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    return Status::error(name + ": " + (err.empty() ? std::string("cannot parse OBJ") : err));
  }
  const auto& positions = reader.GetAttrib().vertices;
  const size_t vertexCount = positions.size() / 3;
  Mesh mesh;
  mesh.vertices.resize(vertexCount);
  for (size_t i = 0; i < vertexCount; ++i) {
    const glm::vec3 p(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return Status::error(name + ": vertex " + std::to_string(i + 1) +
                           " has a non-finite coordinate");
    mesh.vertices[i].position = p;
  }
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (const tinyobj::index_t& idx : shape.mesh.indices) {
      if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= vertexCount)
        return Status::error(name + ": a face of '" + shape.name + "' refers to vertex " +
                             std::to_string(idx.vertex_index + 1) + " of " +
                             std::to_string(vertexCount));
      mesh.indices.push_back(uint32_t(idx.vertex_index));
    }
  }
  if (mesh.indices.empty()) return Status::error(name + ": no triangles");
  if (mesh.indices.size() % 3 != 0) return Status::error(name + ": faces are not triangles");
  computeVertexNormals(mesh);
  out = std::move(mesh);
  return Status::ok();
}

tinyobj::ObjReaderConfig readerConfig() {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  return config;
}

}  // namespace

glm::vec3 Mesh::boundsMin() const {
  glm::vec3 m(std::numeric_limits<float>::infinity());
  for (const MeshVertex& v : vertices) m = glm::min(m, v.position);
  return m;
}

glm::vec3 Mesh::boundsMax() const {
  glm::vec3 m(-std::numeric_limits<float>::infinity());
  for (const MeshVertex& v : vertices) m = glm::max(m, v.position);
  return m;
}

Status loadObj(const std::string& path, Mesh& out) {
  tinyobj::ObjReader reader;
  const bool ok = reader.ParseFromFile(path, readerConfig());
  return fromReader(reader, ok, path, out);
}

Status parseObj(std::string_view text, const std::string& name, Mesh& out) {
  tinyobj::ObjReader reader;
  const bool ok = reader.ParseFromString(std::string(text), "", readerConfig());
  return fromReader(reader, ok, name, out);
}

void computeVertexNormals(Mesh& mesh) {
  std::vector<glm::dvec3> sums(mesh.vertices.size(), glm::dvec3(0.0));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const glm::dvec3 pa(mesh.vertices[a].position), pb(mesh.vertices[b].position),
        pc(mesh.vertices[c].position);
    const glm::dvec3 n = glm::cross(pb - pa, pc - pa);  // length = twice the area
    sums[a] += n;
    sums[b] += n;
    sums[c] += n;
  }
  for (size_t i = 0; i < sums.size(); ++i) {
    const double len = glm::length(sums[i]);
    mesh.vertices[i].normal = len > 0 ? glm::vec3(sums[i] / len) : glm::vec3(0, 0, 1);
  }
}

const Mesh& embeddedBunny() {
  static const Mesh mesh = [] {
    Mesh m;
    Status s = parseObj(kEmbeddedBunnyLowresObj, "embedded bunny_lowres.obj", m);
    (void)s;  // the embedded file is checked by a test
    return m;
  }();
  return mesh;
}

}  // namespace rast
