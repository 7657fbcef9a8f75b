// Scene files: the shipped scenes load, round-trip through JSON unchanged, and scenes/default.json
// renders bit for bit like the built-in default scene; every malformed file gets one message
// naming the file, the JSON pointer and what was expected. Camera animation frame by frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "scene/animation.h"
#include "scene/frame.h"
#include "scene/scene_file.h"
#include "tool_process.h"

namespace rast {
namespace {

namespace fs = std::filesystem;
using testing_tools::TempFolder;

const std::string kScenes = RASTER_SCENES_DIR;

TEST(SceneFile, DefaultSceneFileRendersLikeTheBuiltInScene) {
  SceneDescription file;
  ASSERT_TRUE(loadSceneFile(kScenes + "/default.json", file).isOk());
  ASSERT_EQ(file.draws.size(), 3u);

  PipelineState state;
  state.viewport = {0, 0, file.width, file.height};
  Framebuffer expected(file.width, file.height);
  PipelineStatistics expectedStats;
  ASSERT_TRUE(renderScene(defaultScene(), expected, state, ShadingMode::Lambert, expectedStats));

  Framebuffer actual(file.width, file.height);
  FrameRecord record;
  ASSERT_TRUE(renderFrame(planFrame(file, file.camera), actual, record).isOk());
  EXPECT_TRUE(actual.colorPlane() == expected.colorPlane());
  ASSERT_EQ(actual.depthPlane().size(), expected.depthPlane().size());
  EXPECT_EQ(std::memcmp(actual.depthPlane().data(), expected.depthPlane().data(),
                        actual.depthPlane().size() * sizeof(float)),
            0);
  EXPECT_EQ(record.total, expectedStats) << record.total.toJson() << "\nvs\n" << expectedStats.toJson();
  EXPECT_EQ(record.total.inputTriangles, 3677u);  // 2 + 1 + 3,674 (bunny)
  PipelineStatistics sum;
  for (const DrawRecord& d : record.draws) sum += d.stats;
  EXPECT_EQ(sum, record.total);
}

TEST(SceneFile, ShippedScenesRoundTrip) {
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    SCOPED_TRACE(entry.path().string());
    SceneDescription a, b;
    ASSERT_TRUE(loadSceneFile(entry.path().string(), a).isOk());
    const std::string json = sceneToJson(a);
    ASSERT_TRUE(parseSceneFile(json, entry.path().string(), b).isOk());
    EXPECT_TRUE(sameDescription(a, b));
    EXPECT_EQ(sceneToJson(b), json);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
      EXPECT_EQ(a.meshes[i].mesh.indices, b.meshes[i].mesh.indices);
      EXPECT_EQ(a.meshes[i].mesh.vertices.size(), b.meshes[i].mesh.vertices.size());
    }
  }
}

// Every field away from its default, so that a field the writer forgets cannot pass.
TEST(SceneFile, EveryFieldRoundTrips) {
  SceneDescription s;
  s.description = "all fields";
  s.width = 33;
  s.height = 17;
  s.samples = 4;
  s.background = {0.1f, 0.2f, 0.3f, 0.4f};
  s.clearDepth = 0.25f;
  s.camera.eye = {1.5f, -2.25f, 3.1f};
  s.camera.target = {0.1f, 0.2f, 0.3f};
  s.camera.up = {0, 0, 1};
  s.camera.fovYDegrees = 61.5f;
  s.camera.nearPlane = 0.3f;
  s.camera.farPlane = 77.7f;
  s.lights = {{{1, 2, 3}, {0.5f, 0.6f, 0.7f}}, {{-1, -2, -3}, {1, 1, 1}}};
  NamedMesh quad;
  quad.name = "quad/with~odd name";
  quad.source.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.source.indices = {0, 1, 2, 0, 2, 3};
  NamedMesh bunny;
  bunny.name = "bunny";
  bunny.source.kind = MeshSource::Kind::Builtin;
  bunny.source.path = "bunny_lowres";
  s.meshes = {quad, bunny};
  DrawSpec d;
  d.label = "first";
  d.mesh = 1;
  d.transform.translate = {1, 2, 3};
  d.transform.rotateAxis = {1, 0, 0};
  d.transform.rotateDegrees = 33.3f;
  d.transform.scale = {2, 3, 4};
  d.state.cullMode = CullMode::Front;
  d.state.frontFace = FrontFace::Clockwise;
  d.state.depth.compare = CompareOp::GreaterEqual;
  d.state.depth.write = false;
  d.state.depth.early = false;
  d.state.colorWrite = false;
  d.state.format = FixedPointFormat::d16_8();
  d.state.blend = BlendState::alphaBlend();
  d.state.colorWriteMask = kWriteRed | kWriteGreen | kWriteBlue;
  d.shader.kind = ShadingMode::Lambert;
  d.shader.albedo = {0.9f, 0.1f, 0.2f};
  d.shader.ambient = {0.01f, 0.02f, 0.03f};
  d.shader.light = 1;
  s.draws.push_back(d);
  DrawSpec e;
  e.label = "second";
  e.mesh = 0;
  e.transform.explicitMatrix = glm::mat4(2.0f);
  e.state.format = FixedPointFormat::withFractionBits(6);
  e.state.blend = BlendState::additive();
  e.state.depth.format = DepthFormat::Unorm16;
  e.state.rasterMode = RasterMode::Float;
  e.shader.kind = ShadingMode::Depth;
  e.shader.depthNear = 0.5f;
  e.shader.depthFar = 0.75f;
  s.draws.push_back(e);
  DrawSpec f = e;
  f.label = "third";
  f.shader = ShaderSpec{};
  f.shader.kind = ShadingMode::Constant;
  f.shader.color = {0.2f, 0.4f, 0.6f, 0.8f};
  s.draws.push_back(f);
  CameraAnimation a;
  a.frames = 9;
  a.motion = PathAnimation{{{0, {0, 0, 5}, {0, 0, 0}}, {8, {1.1f, 2.2f, 3.3f}, {0.5f, 0, 0}}}};
  s.animation = a;

  SceneDescription back;
  const Status parsed = parseSceneFile(sceneToJson(s), "memory.json", back);
  ASSERT_TRUE(parsed.isOk()) << parsed.message() << "\n" << sceneToJson(s);
  EXPECT_EQ(sceneToJson(back), sceneToJson(s));
  EXPECT_EQ(back.description, s.description);
  EXPECT_EQ(back.width, 33);
  EXPECT_EQ(back.height, 17);
  EXPECT_EQ(back.samples, 4);
  EXPECT_TRUE(back.draws[0].state.blend == BlendState::alphaBlend());
  EXPECT_EQ(back.draws[0].state.colorWriteMask, kWriteRed | kWriteGreen | kWriteBlue);
  EXPECT_TRUE(back.draws[1].state.blend == BlendState::additive());
  EXPECT_EQ(back.draws[1].state.format, FixedPointFormat::withFractionBits(6));
  EXPECT_EQ(back.draws[1].state.depth.format, DepthFormat::Unorm16);
  EXPECT_EQ(back.draws[1].state.rasterMode, RasterMode::Float);
  EXPECT_EQ(back.background, s.background);
  EXPECT_EQ(back.clearDepth, s.clearDepth);
  EXPECT_EQ(back.camera.eye, s.camera.eye);
  EXPECT_EQ(back.camera.up, s.camera.up);
  EXPECT_EQ(back.camera.fovYDegrees, s.camera.fovYDegrees);
  EXPECT_EQ(back.camera.nearPlane, s.camera.nearPlane);
  EXPECT_EQ(back.camera.farPlane, s.camera.farPlane);
  EXPECT_EQ(back.lights, s.lights);
  ASSERT_EQ(back.meshes.size(), 2u);
  EXPECT_EQ(back.meshes[0].name, quad.name);
  EXPECT_EQ(back.meshes[0].source, quad.source);
  EXPECT_EQ(back.meshes[1].source, bunny.source);
  EXPECT_EQ(back.meshes[1].mesh.triangleCount(), 3674u);
  ASSERT_EQ(back.draws.size(), 3u);
  const DrawSpec& d2 = back.draws[0];
  EXPECT_EQ(d2.label, "first");
  EXPECT_EQ(d2.mesh, 1u);
  EXPECT_EQ(d2.transform, d.transform);
  EXPECT_EQ(d2.state.cullMode, CullMode::Front);
  EXPECT_EQ(d2.state.frontFace, FrontFace::Clockwise);
  EXPECT_EQ(d2.state.depth.compare, CompareOp::GreaterEqual);
  EXPECT_FALSE(d2.state.depth.write);
  EXPECT_FALSE(d2.state.depth.early);
  EXPECT_FALSE(d2.state.colorWrite);
  EXPECT_EQ(d2.state.format, FixedPointFormat::d16_8());
  EXPECT_EQ(d2.shader, d.shader);
  EXPECT_EQ(back.draws[1].transform, e.transform);
  EXPECT_EQ(back.draws[1].shader, e.shader);
  EXPECT_EQ(back.draws[2].shader, f.shader);
  EXPECT_EQ(back.animation, s.animation);
  EXPECT_EQ(d2.transform.matrix(), d.transform.matrix());
}

// A scene file around `draws` (and `extra` top-level members).
std::string sceneWith(const std::string& draws, const std::string& extra = "") {
  return R"({"lights": [{"position": [0, 5, 5]}],
  "meshes": {"tri": {"positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]]}},
  "draws": )" + draws + extra + "}";
}

std::string errorOf(const std::string& text, const std::string& name = "dir/x.json") {
  SceneDescription s;
  const Status st = parseSceneFile(text, name, s);
  return st.isOk() ? "(accepted)" : st.message();
}

TEST(SceneFile, ErrorsNameFilePointerAndExpectation) {
  const std::string ok = R"([{"mesh": "tri", "shader": "lambert"}])";
  EXPECT_EQ(errorOf(sceneWith(ok)), "(accepted)");
  // Bad enum, with the brief's example pointer.
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "tri", "shader": "lambert"},
                                   {"mesh": "tri", "shader": "lambert", "state": {"cull": "sideways"}}])")),
            R"(dir/x.json: /draws/1/state/cull: expected one of "none", "back", "front", found "sideways")");
  // Unknown keys, at every level: typos must not pass silently.
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "tri", "shader": "lambert", "state": {"cul": "back"}}])")),
            R"(dir/x.json: /draws/0/state/cul: unknown key; expected one of "cull", "front_face", )"
            R"("depth_compare", "depth_write", "early_depth", "color_write", "depth_format", "precision", )"
      R"("raster_mode", "blend", "color_write_mask")");
  EXPECT_EQ(errorOf(sceneWith(ok, R"(, "widht": 3)")).substr(0, 33), "dir/x.json: /widht: unknown key; ");
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "tri", "shader": {"name": "constant", "albedo": [1, 1, 1]}}])")),
            R"(dir/x.json: /draws/0/shader/albedo: unknown key; expected one of "name", "color")");
  // Wrong types.
  EXPECT_EQ(errorOf(sceneWith(ok, R"(, "width": "big")")),
            R"(dir/x.json: /width: expected an integer in 1..16384, found "big")");
  EXPECT_EQ(errorOf(sceneWith(ok, R"(, "width": 0)")),
            "dir/x.json: /width: expected an integer in 1..16384, found 0");
  EXPECT_EQ(errorOf(sceneWith(ok, R"(, "camera": {"eye": [1, 2]})")),
            "dir/x.json: /camera/eye: expected an array of 3 numbers, found an array");
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "tri", "shader": "lambert", "state": {"depth_write": 1}}])")),
            "dir/x.json: /draws/0/state/depth_write: expected true or false, found 1");
  EXPECT_EQ(errorOf(sceneWith(R"({"mesh": "tri"})")),
            "dir/x.json: /draws: expected a non-empty array of draws, found an object");
  EXPECT_EQ(errorOf("[1, 2]"), "dir/x.json: /: expected an object, found an array");
  // Unknown shader, unknown precision, unknown mesh, missing key.
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "tri", "shader": {"name": "phong"}}])")),
            R"(dir/x.json: /draws/0/shader/name: expected one of "lambert", "normals", "depth", )"
            R"("triangle-id", "constant", found "phong")");
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "tri", "shader": "lambert", "state": {"precision": "20.8"}}])")),
            R"(dir/x.json: /draws/0/state/precision: expected one of "27.1", "26.2", "25.3", "24.4", )"
      R"("23.5", "22.6", "21.7", "16.8", found "20.8")");
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "triangle", "shader": "lambert"}])")),
            R"(dir/x.json: /draws/0/mesh: expected a mesh named in /meshes: one of "tri", found "triangle")");
  EXPECT_EQ(errorOf(sceneWith(R"([{"shader": "lambert"}])")),
            R"(dir/x.json: /draws/0: missing key "mesh")");
  EXPECT_EQ(errorOf(R"({"meshes": {"m": "builtin:teapot"}, "draws": []})"),
            R"(dir/x.json: /meshes/m: expected a built-in mesh: one of "builtin:bunny_lowres", found "builtin:teapot")");
  EXPECT_EQ(errorOf(R"({"meshes": {"m": {"positions": [[0,0,0],[1,0,0],[0,1,0]], "triangles": [[0,1,3]]}}, "draws": []})"),
            "dir/x.json: /meshes/m/triangles/0/2: expected an integer in 0..2, found 3");
  // Inconsistent values.
  EXPECT_EQ(errorOf(R"({"meshes": {"tri": "builtin:bunny_lowres"}, "draws": [{"mesh": "tri", "shader": "lambert"}]})"),
            "dir/x.json: /draws/0/shader: lambert reads light 0 but the scene has 0 light(s)");
  EXPECT_EQ(errorOf(sceneWith(ok, R"(, "camera": {"near": 5, "far": 2})")),
            R"(dir/x.json: /camera: "near" must be smaller than "far")");
  EXPECT_EQ(errorOf(sceneWith(ok, R"(, "animation": {"frames": 4, "orbit": {}, "path": []})")),
            R"(dir/x.json: /animation: expected exactly one of "orbit" and "path")");
  EXPECT_EQ(errorOf(sceneWith(ok, R"(, "animation": {"frames": 4, "path": [
                {"frame": 2, "eye": [0,0,5], "target": [0,0,0]}, {"frame": 1, "eye": [0,0,5], "target": [0,0,0]}]})")),
            "dir/x.json: /animation/path/1/frame: keyframes must be in increasing frame order");
  EXPECT_EQ(errorOf(sceneWith(R"([{"mesh": "tri", "shader": "lambert", "transform": {"matrix": [1], "scale": 2}}])")),
            R"(dir/x.json: /draws/0/transform: "matrix" replaces "translate", "rotate" and "scale")");
}

TEST(SceneFile, InvalidJsonNamesLineAndColumn) {
  const std::string message = errorOf("{\n  \"width\": 3,\n  oops\n}");
  EXPECT_EQ(message.rfind("dir/x.json:3:3: invalid JSON: ", 0), 0u) << message;
  EXPECT_EQ(errorOf("").rfind("dir/x.json:1:1: invalid JSON: ", 0), 0u) << errorOf("");
}

TEST(SceneFile, MeshFilesAreReadRelativeToTheSceneFile) {
  TempFolder dir;
  std::filesystem::create_directories(dir / "meshes");
  dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  dir.write("meshes/bad.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n");
  const std::string good = R"({"lights": [{"position": [0, 5, 5]}], "meshes": {"m": "meshes/tri.obj"},
                               "draws": [{"mesh": "m", "shader": "lambert"}]})";
  const fs::path file = dir.write("scene.json", good);
  SceneDescription s;
  const Status st = loadSceneFile(file.string(), s);
  ASSERT_TRUE(st.isOk()) << st.message();
  EXPECT_EQ(s.meshes[0].mesh.triangleCount(), 1u);
  EXPECT_EQ(s.meshes[0].source.path, "meshes/tri.obj");  // kept as written

  std::string missing = good, bad = good;
  missing.replace(missing.find("meshes/tri.obj"), 14, "meshes/no.obj");
  bad.replace(bad.find("meshes/tri.obj"), 14, "meshes/bad.obj");
  const std::string name = (dir / "scene.json").string();
  EXPECT_EQ(errorOf(missing, name), name + ": /meshes/m: " + (dir / "meshes/no.obj").string() + ": cannot open file");
  EXPECT_EQ(errorOf(bad, name), name + ": /meshes/m: " + (dir / "meshes/bad.obj").string() +
                                    ":2: 'abc' is not a number");
  EXPECT_EQ(errorOf("{}", name), name + R"(: /: missing key "meshes")");

  SceneDescription none;
  EXPECT_EQ(loadSceneFile((dir / "absent.json").string(), none).message(),
            (dir / "absent.json").string() + ": cannot open file");
  EXPECT_EQ(loadSceneFile(dir.path().string(), none).message(), dir.path().string() + ": is a directory");
}

TEST(CameraAnimation, OrbitTurnsEyeTargetAndUpAboutTheAxis) {
  Camera base;
  base.eye = {0, 2, 10};
  base.target = {0, 2, 0};
  CameraAnimation a;
  a.frames = 4;
  a.motion = OrbitAnimation{{0, 2, 0}, {0, 1, 0}, 360.0f};
  const Camera f0 = cameraAtFrame(base, a, 0);
  EXPECT_EQ(f0.eye, base.eye);
  EXPECT_EQ(f0.target, base.target);
  const Camera f1 = cameraAtFrame(base, a, 1);  // a quarter turn about +y: +z goes to +x
  EXPECT_NEAR(f1.eye.x, 10.0f, 1e-5f);
  EXPECT_NEAR(f1.eye.y, 2.0f, 1e-5f);
  EXPECT_NEAR(f1.eye.z, 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(f1.target, base.target), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(f1.up, base.up), 0.0f, 1e-6f);
  const Camera f2 = cameraAtFrame(base, a, 2);
  EXPECT_NEAR(f2.eye.x, 0.0f, 1e-5f);
  EXPECT_NEAR(f2.eye.z, -10.0f, 1e-5f);
}

TEST(CameraAnimation, PathMovesLinearlyAndHoldsAtTheEnds) {
  Camera base;
  CameraAnimation a;
  a.frames = 12;
  a.motion = PathAnimation{{{2, {0, 0, 4}, {0, 0, 0}}, {6, {8, 4, 0}, {4, 0, 0}}}};
  EXPECT_EQ(cameraAtFrame(base, a, 0).eye, glm::vec3(0, 0, 4));
  EXPECT_EQ(cameraAtFrame(base, a, 2).eye, glm::vec3(0, 0, 4));
  EXPECT_EQ(cameraAtFrame(base, a, 4).eye, glm::vec3(4, 2, 2));
  EXPECT_EQ(cameraAtFrame(base, a, 4).target, glm::vec3(2, 0, 0));
  EXPECT_EQ(cameraAtFrame(base, a, 5).eye, glm::vec3(6, 3, 1));
  EXPECT_EQ(cameraAtFrame(base, a, 11).eye, glm::vec3(8, 4, 0));
}

}  // namespace
}  // namespace rast
