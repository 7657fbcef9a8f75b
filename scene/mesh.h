// Indexed triangle meshes: loading OBJ files (through tinyobjloader) and vertex normals.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "pipeline/status.h"
#include "shaders_cpp/mesh_vertex.h"

namespace rast {

struct Mesh {
  std::vector<MeshVertex> vertices;
  std::vector<uint32_t> indices;  // three per triangle

  size_t triangleCount() const { return indices.size() / 3; }
  glm::vec3 boundsMin() const;
  glm::vec3 boundsMax() const;
};

// Loads the triangles of an OBJ file (polygons are triangulated, normals recomputed). Errors name
// the file: unreadable, malformed, no triangles, non-finite coordinates, indices out of range.
Status loadObj(const std::string& path, Mesh& out);
// The same from text in memory; `name` stands for the file in messages.
Status parseObj(std::string_view text, const std::string& name, Mesh& out);

// Area-weighted vertex normals: the normalised sum of the (unnormalised) face normals around each
// vertex. A vertex whose faces cancel out keeps (0, 0, 1).
void computeVertexNormals(Mesh& mesh);

// The mesh compiled into the binary: the 3,674-triangle Stanford bunny (data/bunny_lowres.obj).
const Mesh& embeddedBunny();

}  // namespace rast
