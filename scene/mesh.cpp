#include "scene/mesh.h"
#include "scene/text_file.h"

#include <charconv>
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

// tinyobjloader reads numbers leniently: "v 1 abc 0" and "v nan 1 0" load with 0 in place of the
// bad token, "v 1 0 0 junk" and "f 1 2 3abc" load as if the junk were absent. Such files must be
// rejected, not drawn wrong, so the vertex and face lines are checked here first (with line
// numbers); all other statements are left to tinyobjloader, which ignores what it does not use.
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

bool parseNumber(std::string_view token, double& value) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

bool parseIndex(std::string_view token, bool required) {
  if (token.empty()) return !required;
  long long value;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && value != 0;
}

// A face corner: v, v/vt, v//vn or v/vt/vn, each a nonzero (possibly negative) integer.
bool isFaceCorner(std::string_view token) {
  const size_t s1 = token.find('/');
  if (s1 == std::string_view::npos) return parseIndex(token, true);
  const size_t s2 = token.find('/', s1 + 1);
  if (!parseIndex(token.substr(0, s1), true)) return false;
  if (s2 == std::string_view::npos) return parseIndex(token.substr(s1 + 1), true);
  return parseIndex(token.substr(s1 + 1, s2 - s1 - 1), false) &&
         parseIndex(token.substr(s2 + 1), true);
}

Status checkVertexAndFaceLines(std::string_view text, const std::string& name) {
  size_t lineNumber = 0;
  while (!text.empty()) {
    const size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    ++lineNumber;
    std::vector<std::string_view> tokens;
    for (size_t pos = 0;;) {
      while (pos < line.size() && isSpace(line[pos])) ++pos;
      if (pos == line.size()) break;
      size_t stop = pos;
      while (stop < line.size() && !isSpace(line[stop])) ++stop;
      tokens.push_back(line.substr(pos, stop - pos));
      pos = stop;
    }
    if (tokens.empty()) continue;
    const std::string where = name + ":" + std::to_string(lineNumber) + ": ";
    if (tokens[0] == "v") {
      // x y z, optionally w or r g b (tinyobjloader's vertex colours), or w r g b.
      if (tokens.size() < 4 || tokens.size() > 8)
        return Status::error(where + "a vertex takes 3 to 7 numbers (x y z [w] [r g b]), found " +
                             std::to_string(tokens.size() - 1));
      for (size_t i = 1; i < tokens.size(); ++i) {
        double v;
        if (!parseNumber(tokens[i], v))
          return Status::error(where + "'" + std::string(tokens[i]) + "' is not a number");
        if (!std::isfinite(v)) return Status::error(where + "non-finite coordinate");
      }
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4)
        return Status::error(where + "a face needs at least 3 vertices, found " +
                             std::to_string(tokens.size() - 1));
      for (size_t i = 1; i < tokens.size(); ++i)
        if (!isFaceCorner(tokens[i]))
          return Status::error(where + "'" + std::string(tokens[i]) +
                               "' is not a vertex reference (a nonzero index)");
    }
  }
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
  // Read here rather than by tinyobjloader, so the text can be checked first (materials are not
  // used, so the .mtl files it would look for next to the file are not needed).
  std::string text;
  if (Status s = readTextFile(path, text); !s) return s;
  return parseObj(text, path, out);
}

Status parseObj(std::string_view text, const std::string& name, Mesh& out) {
  if (Status s = checkVertexAndFaceLines(text, name); !s) return s;
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
