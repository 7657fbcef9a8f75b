// Meshes (scene/mesh.h) and window-space triangle lists (scene/triangle_list.h): loading real
// files, the embedded bunny, vertex normals, and the errors bad input gives.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scene/mesh.h"
#include "scene/triangle_list.h"

namespace rast {
namespace {

nlohmann::json meshesJson() {
  std::ifstream f(RASTER_SHARED_MESHES "/meshes.json");
  std::stringstream s;
  s << f.rdbuf();
  return nlohmann::json::parse(s.str());
}

// Every real mesh loads with the counts and bounding box its checker recorded. The box corners
// are coordinates as written in the file, and both sides turn that decimal text into a float the
// same way (to double, then to float), so they compare exactly.
TEST(Mesh, RealMeshesMatchMeshesJson) {
  const nlohmann::json json = meshesJson();
  ASSERT_EQ(json.size(), 9u);
  for (const auto& [file, info] : json.items()) {
    SCOPED_TRACE(file);
    Mesh mesh;
    const Status s = loadObj(RASTER_SHARED_MESHES "/" + file, mesh);
    ASSERT_TRUE(s) << s.message();
    EXPECT_EQ(mesh.triangleCount(), info.at("triangles").get<size_t>());
    EXPECT_EQ(mesh.vertices.size(), info.at("vertices").get<size_t>());
    EXPECT_EQ(mesh.indices.size(), 3 * mesh.triangleCount());
    const glm::vec3 lo = mesh.boundsMin(), hi = mesh.boundsMax();
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(lo[k], float(info.at("bbox_min")[k].get<double>())) << "axis " << k;
      EXPECT_EQ(hi[k], float(info.at("bbox_max")[k].get<double>())) << "axis " << k;
    }
  }
}

// The file's first face is "f 1 2 3"-style 1-based indices; check the first triangle against the
// text itself, so index handling (1-based to 0-based) is pinned, not just counts.
TEST(Mesh, FirstFaceOfBunnyLowres) {
  std::ifstream f(RASTER_SHARED_MESHES "/bunny_lowres.obj");
  std::string line;
  std::vector<glm::vec3> positions;
  uint32_t face[3] = {0, 0, 0};
  while (std::getline(f, line)) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v") {
      glm::vec3 p;
      in >> p.x >> p.y >> p.z;
      positions.push_back(p);
    } else if (tag == "f") {
      in >> face[0] >> face[1] >> face[2];
      break;
    }
  }
  Mesh mesh;
  ASSERT_TRUE(loadObj(RASTER_SHARED_MESHES "/bunny_lowres.obj", mesh));
  for (int k = 0; k < 3; ++k) {
    ASSERT_GE(face[k], 1u);
    EXPECT_EQ(mesh.indices[k], face[k] - 1);
    EXPECT_EQ(mesh.vertices[mesh.indices[k]].position, positions[face[k] - 1]);
  }
}

// The mesh compiled into the binary is the shared bunny_lowres.obj, vertex for vertex.
TEST(Mesh, EmbeddedBunnyEqualsSharedFile) {
  Mesh file;
  const Status s = loadObj(RASTER_SHARED_MESHES "/bunny_lowres.obj", file);
  ASSERT_TRUE(s) << s.message();
  const Mesh& embedded = embeddedBunny();
  ASSERT_EQ(embedded.vertices.size(), file.vertices.size());
  ASSERT_EQ(embedded.indices, file.indices);
  for (size_t i = 0; i < file.vertices.size(); ++i) {
    ASSERT_EQ(embedded.vertices[i].position, file.vertices[i].position) << "vertex " << i;
    ASSERT_EQ(embedded.vertices[i].normal, file.vertices[i].normal) << "vertex " << i;
  }
  EXPECT_EQ(embedded.triangleCount(), 3674u);
}

// Area weighting. Vertices 0 and 1 are shared by triangle (0, 1, 2) in the xy plane, area 2,
// cross product (0, 0, 4), and triangle (0, 1, 3) in the xz plane, area 1, cross product
// cross((2, 0, 0), (0, 0, -1)) = (0, 2, 0). Their sum (0, 2, 4) gives the normal (0, 1, 2) / sqrt(5);
// an unweighted average would give (0, 1, 1) / sqrt(2).
TEST(Mesh, VertexNormalsAreAreaWeighted) {
  Mesh m;
  for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0),
                      glm::vec3(0, 0, -1), glm::vec3(5, 5, 5)})  // vertex 4: used by no face
    m.vertices.push_back({p, {9, 9, 9}});
  m.indices = {0, 1, 2, 0, 1, 3};
  computeVertexNormals(m);
  const glm::vec3 expected0 = glm::vec3(0, 1, 2) / std::sqrt(5.0f);
  for (int k = 0; k < 3; ++k) {
    // Float rounding of one normalisation: a few ulps.
    EXPECT_NEAR(m.vertices[0].normal[k], expected0[k], 1e-6f) << k;
    EXPECT_NEAR(m.vertices[1].normal[k], expected0[k], 1e-6f) << k;
  }
  EXPECT_EQ(m.vertices[2].normal, glm::vec3(0, 0, 1));  // only the +z face
  EXPECT_EQ(m.vertices[3].normal, glm::vec3(0, 1, 0));  // only the +y face
  EXPECT_EQ(m.vertices[4].normal, glm::vec3(0, 0, 1));  // no face: the documented default
}

TEST(Mesh, VertexNormalsThatCancelKeepTheDefault) {
  Mesh m;
  for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)})
    m.vertices.push_back({p, {9, 9, 9}});
  m.indices = {0, 1, 2, 0, 2, 1};  // the same triangle, both windings
  computeVertexNormals(m);
  for (const MeshVertex& v : m.vertices) EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
}

TEST(Mesh, ParseObjTriangulatesAndAcceptsNegativeIndices) {
  Mesh m;
  // The unit square, counter-clockwise seen from +z, as one quad with relative indices.
  const Status s = parseObj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n", "quad", m);
  ASSERT_TRUE(s) << s.message();
  ASSERT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[2].position, glm::vec3(1, 1, 0));
  // Which diagonal tinyobjloader splits along is its business; the two triangles must use the
  // four corners, keep the quad's winding (+z) and tile its area exactly (1 = 0.5 + 0.5).
  ASSERT_EQ(m.triangleCount(), 2u);
  double area = 0;
  for (size_t t = 0; t < 2; ++t) {
    const glm::vec3 a = m.vertices[m.indices[3 * t]].position,
                    b = m.vertices[m.indices[3 * t + 1]].position,
                    c = m.vertices[m.indices[3 * t + 2]].position;
    const glm::vec3 n = glm::cross(b - a, c - a);
    EXPECT_EQ(n, glm::vec3(0, 0, 1)) << "triangle " << t;
    area += 0.5 * n.z;
  }
  EXPECT_EQ(area, 1.0);
  EXPECT_EQ(m.vertices[0].normal, glm::vec3(0, 0, 1));
}

void expectObjError(const std::string& text, const std::string& expected) {
  Mesh m;
  m.indices = {7};
  const Status s = parseObj(text, "t.obj", m);
  EXPECT_FALSE(s) << text;
  EXPECT_EQ(s.message(), expected);
  EXPECT_EQ(m.indices, std::vector<uint32_t>{7}) << "output changed on error";
}

TEST(Mesh, ObjErrorsNameTheLine) {
  expectObjError("v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n", "t.obj:2: 'abc' is not a number");
  expectObjError("v 0 0 0\nv 1 0 0 junk\nv 0 1 0\nf 1 2 3\n", "t.obj:2: 'junk' is not a number");
  expectObjError("v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "t.obj:3: non-finite coordinate");
  expectObjError("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
                 "t.obj:2: a vertex takes 3 to 7 numbers (x y z [w] [r g b]), found 2");
  expectObjError("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3abc\n",
                 "t.obj:5: '3abc' is not a vertex reference (a nonzero index)");
  expectObjError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                 "t.obj:4: '0' is not a vertex reference (a nonzero index)");
  expectObjError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
                 "t.obj:4: a face needs at least 3 vertices, found 2");
  expectObjError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "t.obj: a face of '' refers to vertex 4 of 3");
  expectObjError("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "t.obj: no triangles");
  expectObjError("hello world\n", "t.obj: no triangles");
  // Beyond float: the coordinate is finite as text and as double, infinite as float.
  expectObjError("v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj: vertex 2 has a non-finite coordinate");
}

TEST(Mesh, ObjFaceCornerForms) {
  Mesh m;
  const Status s = parseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1 2/1/1 3//1\n", "forms", m);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(Mesh, LoadObjMissingFile) {
  Mesh m;
  const Status s = loadObj("/nonexistent/file.obj", m);
  EXPECT_FALSE(s);
  EXPECT_EQ(s.message(), "/nonexistent/file.obj: cannot open file");
  const Status d = loadObj(RASTER_SHARED_MESHES, m);
  EXPECT_EQ(d.message(), std::string(RASTER_SHARED_MESHES) + ": is a directory");
}

// Window-space triangle lists.

TEST(TriangleList, ParsesValuesCommentsAndBlankLines) {
  std::vector<WindowVertex> v;
  const Status s = parseTriangleList(
      "# comment\n\n  0 0 0.5\t4 0 0.5 4 4 0.5\r\n-1.5 2e1 1 3 4 0 5 6 0.25\n", "list", v);
  ASSERT_TRUE(s) << s.message();
  ASSERT_EQ(v.size(), 6u);
  EXPECT_EQ(v[0].position, glm::vec3(0, 0, 0.5f));
  EXPECT_EQ(v[2].position, glm::vec3(4, 4, 0.5f));
  EXPECT_EQ(v[3].position, glm::vec3(-1.5f, 20, 1));
  EXPECT_EQ(v[5].position, glm::vec3(5, 6, 0.25f));
}

void expectListError(const std::string& text, const std::string& expected) {
  std::vector<WindowVertex> v(1);
  const Status s = parseTriangleList(text, "t.txt", v);
  EXPECT_FALSE(s) << text;
  EXPECT_EQ(s.message(), expected);
  EXPECT_EQ(v.size(), 1u) << "output changed on error";
}

TEST(TriangleList, ErrorsNameFileAndLine) {
  const std::string good = "0 0 0 1 0 0 0 1 0\n";
  expectListError(good + "# c\n1 2 3 4 5 6 7\n",
                  "t.txt:3: expected 9 numbers (x y z for 3 vertices), found 7");
  expectListError(good + good + "0 0 0 1 0 0 0 1 0 9\n", "t.txt:3: more than 9 numbers");
  expectListError("0 0 0 1 x 0 0 1 0\n", "t.txt:1: 'x' is not a number");
  expectListError("\n0 0 0 1 0 0 0 1 0.5z\n", "t.txt:2: '0.5z' is not a number");
  expectListError(good + "0 0 nan 1 0 0 0 1 0\n", "t.txt:2: non-finite coordinate");
  expectListError(good + "0 0 0 1 0 0 0 inf 0\n", "t.txt:2: non-finite coordinate");
  expectListError(good + "0 0 0 1 0 0 0 1e39 0\n", "t.txt:2: '1e39' is out of the float range");
  expectListError("# only a comment\n\n", "t.txt: no triangles");
}

TEST(TriangleList, LoadMissingFile) {
  std::vector<WindowVertex> v;
  const Status s = loadTriangleList("/nonexistent/list.txt", v);
  EXPECT_FALSE(s);
  EXPECT_EQ(s.message(), "/nonexistent/list.txt: cannot open file");
}

}  // namespace
}  // namespace rast
