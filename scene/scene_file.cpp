#include "scene/scene_file.h"
#include "scene/text_file.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

namespace rast {
namespace {

using Json = nlohmann::ordered_json;

// Thrown inside this file only, so that the readers below stay straight-line; parseSceneFile
// turns it into a Status.
struct SceneError {
  std::string message;
};

template <class T>
using Names = std::vector<std::pair<const char*, T>>;

const Names<CullMode> kCullModes = {
    {"none", CullMode::None}, {"back", CullMode::Back}, {"front", CullMode::Front}};
const Names<FrontFace> kFrontFaces = {{"ccw", FrontFace::CounterClockwise},
                                      {"cw", FrontFace::Clockwise}};
const Names<CompareOp> kCompareOps = {
    {"never", CompareOp::Never},     {"less", CompareOp::Less},
    {"equal", CompareOp::Equal},     {"less-equal", CompareOp::LessEqual},
    {"greater", CompareOp::Greater}, {"not-equal", CompareOp::NotEqual},
    {"greater-equal", CompareOp::GreaterEqual}, {"always", CompareOp::Always}};
const Names<FixedPointFormat> kPrecisions = {
    {"27.1", FixedPointFormat::withFractionBits(1)}, {"26.2", FixedPointFormat::withFractionBits(2)},
    {"25.3", FixedPointFormat::withFractionBits(3)}, {"24.4", FixedPointFormat::d24_4()},
    {"23.5", FixedPointFormat::withFractionBits(5)}, {"22.6", FixedPointFormat::withFractionBits(6)},
    {"21.7", FixedPointFormat::withFractionBits(7)}, {"16.8", FixedPointFormat::d16_8()}};
const Names<BlendState> kBlendModes = {{"none", BlendState{}},
                                       {"alpha", BlendState::alphaBlend()},
                                       {"additive", BlendState::additive()}};
const Names<DepthFormat> kDepthFormats = {{"float32", DepthFormat::Float32},
                                          {"unorm24", DepthFormat::Unorm24},
                                          {"unorm16", DepthFormat::Unorm16}};
const Names<RasterMode> kRasterModes = {{"fixed-point", RasterMode::FixedPoint},
                                        {"float", RasterMode::Float}};
const Names<uint8_t> kWriteMasks = {{"rgba", uint8_t(kWriteAll)},
                                    {"rgb", uint8_t(kWriteRed | kWriteGreen | kWriteBlue)},
                                    {"alpha", uint8_t(kWriteAlpha)},
                                    {"none", uint8_t(kWriteNone)}};
const Names<ShadingMode> kShadingModes = {
    {"lambert", ShadingMode::Lambert}, {"normals", ShadingMode::Normals},
    {"depth", ShadingMode::Depth},     {"triangle-id", ShadingMode::TriangleId},
    {"constant", ShadingMode::Constant}};
const std::vector<std::string> kBuiltinMeshes = {"bunny_lowres"};

template <class T>
const char* nameOf(const Names<T>& names, T value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

template <class Range>
std::string quotedList(const Range& names) {
  std::string s;
  for (const auto& n : names) {
    if (!s.empty()) s += ", ";
    s += '"';
    s += n;
    s += '"';
  }
  return s;
}

// A value in the document with its JSON pointer, for messages.
class Node {
 public:
  Node(const Json& json, std::string pointer, const std::string& file)
      : json_(json), pointer_(std::move(pointer)), file_(file) {}

  const Json& json() const { return json_; }
  const std::string& pointer() const { return pointer_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw SceneError{file_ + ": " + (pointer_.empty() ? "/" : pointer_) + ": " + what};
  }
  [[noreturn]] void expected(const std::string& what) const {
    fail("expected " + what + ", found " + describe());
  }

  // An object whose keys are all among `allowed` (typos must not pass silently).
  void expectObject(const std::vector<const char*>& allowed) const {
    if (!json_.is_object()) expected("an object");
    for (const auto& [key, value] : json_.items()) {
      bool known = false;
      for (const char* a : allowed) known |= key == a;
      if (!known) child(key).fail("unknown key; expected one of " + quotedList(allowed));
    }
  }
  std::optional<Node> find(const char* key) const {
    const auto it = json_.find(key);
    if (it == json_.end()) return std::nullopt;
    return child(key);
  }
  Node required(const char* key) const {
    if (std::optional<Node> n = find(key)) return *n;
    fail(std::string("missing key \"") + key + "\"");
  }
  size_t arraySize(size_t min, size_t max, const std::string& what) const {
    if (!json_.is_array() || json_.size() < min || json_.size() > max) expected(what);
    return json_.size();
  }
  Node operator[](size_t i) const {
    return Node(json_[i], pointer_ + "/" + std::to_string(i), file_);
  }

  float number() const {
    if (!json_.is_number()) expected("a number");
    const double v = json_.get<double>();
    if (!std::isfinite(v) || std::abs(v) > std::numeric_limits<float>::max())
      expected("a number in the float range");
    return float(v);
  }
  float positive() const {
    const float v = number();
    if (!(v > 0)) expected("a positive number");
    return v;
  }
  int integer(int min, int max) const {
    if (!json_.is_number_integer() || json_.get<int64_t>() < min || json_.get<int64_t>() > max)
      expected("an integer in " + std::to_string(min) + ".." + std::to_string(max));
    return int(json_.get<int64_t>());
  }
  bool boolean() const {
    if (!json_.is_boolean()) expected("true or false");
    return json_.get<bool>();
  }
  std::string string() const {
    if (!json_.is_string()) expected("a string");
    return json_.get<std::string>();
  }
  glm::vec3 vec3() const {
    arraySize(3, 3, "an array of 3 numbers");
    return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
  }
  glm::vec3 direction() const {
    const glm::vec3 v = vec3();
    if (v == glm::vec3(0.0f)) expected("a nonzero vector");
    return v;
  }
  // RGB or RGBA; alpha defaults to 1.
  glm::vec4 color() const {
    const size_t n = arraySize(3, 4, "an array of 3 or 4 numbers (RGB or RGBA)");
    return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number(),
            n == 4 ? (*this)[3].number() : 1.0f};
  }
  template <class T>
  T choice(const Names<T>& names) const {
    if (json_.is_string())
      for (const auto& [name, value] : names)
        if (json_.get<std::string>() == name) return value;
    std::vector<const char*> list;
    for (const auto& n : names) list.push_back(n.first);
    expected("one of " + quotedList(list));
  }

 private:
  Node child(const std::string& key) const {
    std::string escaped;
    for (char c : key) escaped += c == '~' ? "~0" : (c == '/' ? "~1" : std::string(1, c));
    return Node(json_.at(key), pointer_ + "/" + escaped, file_);
  }
  std::string describe() const {
    if (json_.is_array()) return "an array";
    if (json_.is_object()) return "an object";
    std::string text = json_.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
  }

  const Json& json_;
  std::string pointer_;
  const std::string& file_;
};

// Floats written as the shortest decimal that reads back as the same float.
Json number(float v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  double d = 0;
  std::from_chars(buffer, end, d);
  return d;
}
Json array(glm::vec3 v) { return Json::array({number(v.x), number(v.y), number(v.z)}); }
Json array(glm::vec4 v) { return Json::array({number(v.x), number(v.y), number(v.z), number(v.w)}); }

// ---- Per-draw pipeline state: one entry per key. A new state field is one line in
// stateFields() with the codec of its type, e.g.
//   integerField("samples", [](auto& s) -> auto& { return s.samples; }, {1, 2, 4, 8}),
//   choiceField("depth_format", [](auto& s) -> auto& { return s.depthFormat; }, kDepthFormats),

struct StateField {
  const char* key;
  std::function<void(const Node&, PipelineState&)> read;
  std::function<Json(const PipelineState&)> write;
};

template <class Get, class T>
StateField choiceField(const char* key, Get get, const Names<T>& names) {
  return {key, [get, &names](const Node& n, PipelineState& s) { get(s) = n.choice(names); },
          [get, &names](const PipelineState& s) { return Json(nameOf(names, get(s))); }};
}

template <class Get>
StateField boolField(const char* key, Get get) {
  return {key, [get](const Node& n, PipelineState& s) { get(s) = n.boolean(); },
          [get](const PipelineState& s) { return Json(get(s)); }};
}

// For counts such as MSAA samples: an integer from `allowed`.
template <class Get>
StateField integerField(const char* key, Get get, std::vector<int> allowed) {
  return {key,
          [get, allowed](const Node& n, PipelineState& s) {
            for (int a : allowed)
              if (n.json().is_number_integer() && n.json().get<int64_t>() == a) {
                get(s) = a;
                return;
              }
            std::string list;
            for (int a : allowed) list += (list.empty() ? "" : ", ") + std::to_string(a);
            n.expected("one of " + list);
          },
          [get](const PipelineState& s) { return Json(get(s)); }};
}

const std::vector<StateField>& stateFields() {
  static const std::vector<StateField> fields = {
      choiceField("cull", [](auto& s) -> auto& { return s.cullMode; }, kCullModes),
      choiceField("front_face", [](auto& s) -> auto& { return s.frontFace; }, kFrontFaces),
      choiceField("depth_compare", [](auto& s) -> auto& { return s.depth.compare; }, kCompareOps),
      boolField("depth_write", [](auto& s) -> auto& { return s.depth.write; }),
      boolField("early_depth", [](auto& s) -> auto& { return s.depth.early; }),
      boolField("color_write", [](auto& s) -> auto& { return s.colorWrite; }),
      choiceField("depth_format", [](auto& s) -> auto& { return s.depth.format; }, kDepthFormats),
      choiceField("precision", [](auto& s) -> auto& { return s.format; }, kPrecisions),
      choiceField("raster_mode", [](auto& s) -> auto& { return s.rasterMode; }, kRasterModes),
      choiceField("blend", [](auto& s) -> auto& { return s.blend; }, kBlendModes),
      choiceField("color_write_mask", [](auto& s) -> auto& { return s.colorWriteMask; },
                  kWriteMasks),
  };
  return fields;
}

PipelineState readState(const Node& n) {
  std::vector<const char*> keys;
  for (const StateField& f : stateFields()) keys.push_back(f.key);
  n.expectObject(keys);
  PipelineState state;
  for (const StateField& f : stateFields())
    if (std::optional<Node> v = n.find(f.key)) f.read(*v, state);
  return state;
}

Json writeState(const PipelineState& state) {
  Json j = Json::object();
  for (const StateField& f : stateFields()) j[f.key] = f.write(state);
  return j;
}

// ---- Shaders: the keys each one takes.

std::vector<const char*> shaderKeys(ShadingMode kind) {
  switch (kind) {
    case ShadingMode::Lambert: return {"name", "albedo", "ambient", "light"};
    case ShadingMode::Constant: return {"name", "color"};
    case ShadingMode::Depth: return {"name", "near", "far"};
    default: return {"name"};
  }
}

ShaderSpec readShader(const Node& n, size_t lightCount) {
  ShaderSpec s;
  if (n.json().is_string()) {
    s.kind = n.choice(kShadingModes);
  } else {
    if (!n.json().is_object()) n.expected("a shader name or an object with \"name\"");
    s.kind = n.required("name").choice(kShadingModes);
    n.expectObject(shaderKeys(s.kind));
    if (auto v = n.find("albedo")) s.albedo = v->vec3();
    if (auto v = n.find("ambient")) s.ambient = v->vec3();
    if (auto v = n.find("light")) s.light = v->integer(0, 1 << 20);
    if (auto v = n.find("color")) s.color = v->color();
    if (auto v = n.find("near")) s.depthNear = v->number();
    if (auto v = n.find("far")) s.depthFar = v->number();
    if (s.kind == ShadingMode::Depth && !(s.depthNear != s.depthFar))
      n.fail("\"near\" and \"far\" must differ");
  }
  if (s.kind == ShadingMode::Lambert && size_t(s.light) >= lightCount)
    n.fail("lambert reads light " + std::to_string(s.light) + " but the scene has " +
           std::to_string(lightCount) + " light(s)");
  return s;
}

Json writeShader(const ShaderSpec& s) {
  Json j = Json::object();
  j["name"] = shadingModeName(s.kind);
  if (s.kind == ShadingMode::Lambert) {
    j["albedo"] = array(s.albedo);
    j["ambient"] = array(s.ambient);
    j["light"] = s.light;
  } else if (s.kind == ShadingMode::Constant) {
    j["color"] = array(s.color);
  } else if (s.kind == ShadingMode::Depth) {
    j["near"] = number(s.depthNear);
    j["far"] = number(s.depthFar);
  }
  return j;
}

// ---- Meshes.

NamedMesh readMesh(const Node& n, const std::string& name, const std::string& directory) {
  NamedMesh m;
  m.name = name;
  if (n.json().is_string()) {
    const std::string s = n.string();
    if (s.rfind("builtin:", 0) == 0) {
      m.source.kind = MeshSource::Kind::Builtin;
      m.source.path = s.substr(8);
      if (m.source.path != "bunny_lowres")
        n.expected("a built-in mesh: one of " + quotedList(std::vector<std::string>{"builtin:bunny_lowres"}));
      m.mesh = embeddedBunny();
    } else {
      m.source.kind = MeshSource::Kind::File;
      m.source.path = s;
      const std::filesystem::path file = std::filesystem::path(directory) / s;
      if (Status st = loadObj(file.lexically_normal().string(), m.mesh); !st) n.fail(st.message());
    }
    return m;
  }
  if (!n.json().is_object())
    n.expected("an OBJ path, \"builtin:NAME\" or an object with \"positions\" and \"triangles\"");
  n.expectObject({"positions", "triangles"});
  m.source.kind = MeshSource::Kind::Inline;
  const Node positions = n.required("positions");
  const size_t vertexCount = positions.arraySize(3, 1u << 24, "an array of at least 3 positions");
  for (size_t i = 0; i < vertexCount; ++i) m.source.positions.push_back(positions[i].vec3());
  const Node triangles = n.required("triangles");
  const size_t triangleCount = triangles.arraySize(1, 1u << 24, "a non-empty array of triangles");
  for (size_t t = 0; t < triangleCount; ++t) {
    const Node tri = triangles[t];
    tri.arraySize(3, 3, "3 vertex indices");
    for (size_t k = 0; k < 3; ++k)
      m.source.indices.push_back(uint32_t(tri[k].integer(0, int(vertexCount) - 1)));
  }
  for (const glm::vec3& p : m.source.positions) m.mesh.vertices.push_back({p, {0, 0, 1}});
  m.mesh.indices = m.source.indices;
  computeVertexNormals(m.mesh);
  return m;
}

Json writeMesh(const MeshSource& s) {
  switch (s.kind) {
    case MeshSource::Kind::File: return s.path;
    case MeshSource::Kind::Builtin: return "builtin:" + s.path;
    case MeshSource::Kind::Inline: break;
  }
  Json positions = Json::array(), triangles = Json::array();
  for (const glm::vec3& p : s.positions) positions.push_back(array(p));
  for (size_t i = 0; i + 2 < s.indices.size(); i += 3)
    triangles.push_back(Json::array({s.indices[i], s.indices[i + 1], s.indices[i + 2]}));
  return Json{{"positions", positions}, {"triangles", triangles}};
}

// ---- Transform, camera, animation.

Transform readTransform(const Node& n) {
  n.expectObject({"translate", "rotate", "scale", "matrix"});
  Transform t;
  if (auto m = n.find("matrix")) {
    if (n.json().size() != 1) n.fail("\"matrix\" replaces \"translate\", \"rotate\" and \"scale\"");
    m->arraySize(16, 16, "an array of 16 numbers (column-major)");
    glm::mat4 matrix;
    for (int i = 0; i < 16; ++i) matrix[i / 4][i % 4] = (*m)[size_t(i)].number();
    t.explicitMatrix = matrix;
    return t;
  }
  if (auto v = n.find("translate")) t.translate = v->vec3();
  if (auto r = n.find("rotate")) {
    r->expectObject({"axis", "degrees"});
    t.rotateAxis = r->required("axis").direction();
    t.rotateDegrees = r->required("degrees").number();
  }
  if (auto v = n.find("scale")) t.scale = v->json().is_number() ? glm::vec3(v->number()) : v->vec3();
  return t;
}

Json writeTransform(const Transform& t) {
  if (t.explicitMatrix) {
    Json m = Json::array();
    for (int i = 0; i < 16; ++i) m.push_back(number((*t.explicitMatrix)[i / 4][i % 4]));
    return Json{{"matrix", m}};
  }
  return Json{{"translate", array(t.translate)},
              {"rotate", {{"axis", array(t.rotateAxis)}, {"degrees", number(t.rotateDegrees)}}},
              {"scale", array(t.scale)}};
}

Camera readCamera(const Node& n) {
  n.expectObject({"eye", "target", "up", "fov", "near", "far"});
  Camera c;
  if (auto v = n.find("eye")) c.eye = v->vec3();
  if (auto v = n.find("target")) c.target = v->vec3();
  if (auto v = n.find("up")) c.up = v->direction();
  if (auto v = n.find("fov")) {
    c.fovYDegrees = v->number();
    if (!(c.fovYDegrees > 0 && c.fovYDegrees < 180)) v->expected("degrees in (0, 180)");
  }
  if (auto v = n.find("near")) c.nearPlane = v->positive();
  if (auto v = n.find("far")) c.farPlane = v->positive();
  if (!(c.nearPlane < c.farPlane)) n.fail("\"near\" must be smaller than \"far\"");
  if (c.eye == c.target) n.fail("\"eye\" and \"target\" must differ");
  return c;
}

Json writeCamera(const Camera& c) {
  return Json{{"eye", array(c.eye)},           {"target", array(c.target)},
              {"up", array(c.up)},             {"fov", number(c.fovYDegrees)},
              {"near", number(c.nearPlane)},   {"far", number(c.farPlane)}};
}

CameraAnimation readAnimation(const Node& n) {
  n.expectObject({"frames", "orbit", "path"});
  CameraAnimation a;
  a.frames = n.required("frames").integer(1, 1000000);
  const std::optional<Node> orbit = n.find("orbit"), path = n.find("path");
  if (orbit.has_value() == path.has_value()) n.fail("expected exactly one of \"orbit\" and \"path\"");
  if (orbit) {
    orbit->expectObject({"centre", "axis", "degrees"});
    OrbitAnimation o;
    if (auto v = orbit->find("centre")) o.centre = v->vec3();
    if (auto v = orbit->find("axis")) o.axis = v->direction();
    if (auto v = orbit->find("degrees")) o.degrees = v->number();
    a.motion = o;
  } else {
    PathAnimation p;
    const size_t count = path->arraySize(1, 1u << 20, "a non-empty array of keyframes");
    for (size_t i = 0; i < count; ++i) {
      const Node k = (*path)[i];
      k.expectObject({"frame", "eye", "target"});
      CameraKeyframe key;
      const Node frame = k.required("frame");
      key.frame = frame.integer(0, a.frames - 1);
      if (!p.keyframes.empty() && key.frame <= p.keyframes.back().frame)
        frame.fail("keyframes must be in increasing frame order");
      key.eye = k.required("eye").vec3();
      key.target = k.required("target").vec3();
      if (key.eye == key.target) k.fail("\"eye\" and \"target\" must differ");
      p.keyframes.push_back(key);
    }
    a.motion = p;
  }
  return a;
}

Json writeAnimation(const CameraAnimation& a) {
  Json j{{"frames", a.frames}};
  if (const auto* o = std::get_if<OrbitAnimation>(&a.motion)) {
    j["orbit"] = {{"centre", array(o->centre)}, {"axis", array(o->axis)}, {"degrees", number(o->degrees)}};
  } else {
    Json keys = Json::array();
    for (const CameraKeyframe& k : std::get<PathAnimation>(a.motion).keyframes)
      keys.push_back({{"frame", k.frame}, {"eye", array(k.eye)}, {"target", array(k.target)}});
    j["path"] = keys;
  }
  return j;
}

// ---- The whole file.

SceneDescription readScene(const Node& root, const std::string& directory) {
  root.expectObject({"description", "width", "height", "samples", "background", "clear_depth",
                     "camera", "lights", "meshes", "draws", "animation"});
  SceneDescription s;
  s.directory = directory;
  if (auto v = root.find("description")) s.description = v->string();
  if (auto v = root.find("width")) s.width = v->integer(1, 16384);
  if (auto v = root.find("height")) s.height = v->integer(1, 16384);
  if (auto v = root.find("samples")) {
    s.samples = v->integer(1, 8);
    if (!SamplePattern::supported(s.samples)) v->expected("1, 4 or 8 samples per pixel");
  }
  if (auto v = root.find("background")) s.background = v->color();
  if (auto v = root.find("clear_depth")) s.clearDepth = v->number();
  if (auto v = root.find("camera")) s.camera = readCamera(*v);
  if (auto lights = root.find("lights")) {
    const size_t count = lights->arraySize(0, 1024, "an array of lights");
    for (size_t i = 0; i < count; ++i) {
      const Node l = (*lights)[i];
      l.expectObject({"position", "color"});
      PointLight light;
      light.position = l.required("position").vec3();
      if (auto c = l.find("color")) light.color = c->vec3();
      s.lights.push_back(light);
    }
  }
  const Node meshes = root.required("meshes");
  if (!meshes.json().is_object() || meshes.json().empty())
    meshes.expected("an object naming at least one mesh");
  for (const auto& [name, value] : meshes.json().items()) {
    (void)value;
    s.meshes.push_back(readMesh(*meshes.find(name.c_str()), name, directory));
  }
  const Node draws = root.required("draws");
  const size_t drawCount = draws.arraySize(1, 1u << 16, "a non-empty array of draws");
  for (size_t i = 0; i < drawCount; ++i) {
    const Node d = draws[i];
    d.expectObject({"label", "mesh", "transform", "state", "shader"});
    DrawSpec draw;
    const Node mesh = d.required("mesh");
    const std::string meshName = mesh.string();
    size_t index = 0;
    while (index < s.meshes.size() && s.meshes[index].name != meshName) ++index;
    if (index == s.meshes.size()) {
      std::vector<std::string> names;
      for (const NamedMesh& m : s.meshes) names.push_back(m.name);
      mesh.expected("a mesh named in /meshes: one of " + quotedList(names));
    }
    draw.mesh = index;
    draw.label = meshName;
    if (auto v = d.find("label")) draw.label = v->string();
    if (auto v = d.find("transform")) draw.transform = readTransform(*v);
    if (auto v = d.find("state")) draw.state = readState(*v);
    draw.shader = readShader(d.required("shader"), s.lights.size());
    s.draws.push_back(std::move(draw));
  }
  if (auto v = root.find("animation")) s.animation = readAnimation(*v);
  return s;
}

}  // namespace

glm::mat4 Transform::matrix() const {
  if (explicitMatrix) return *explicitMatrix;
  glm::mat4 m(1.0f);
  if (translate != glm::vec3(0.0f)) m = glm::translate(m, translate);
  if (rotateDegrees != 0.0f) m = glm::rotate(m, glm::radians(rotateDegrees), glm::normalize(rotateAxis));
  if (scale != glm::vec3(1.0f)) m = glm::scale(m, scale);
  return m;
}

float SceneDescription::resolvedClearDepth() const {
  if (clearDepth) return *clearDepth;
  if (draws.empty()) return 1.0f;
  const CompareOp op = draws.front().state.depth.compare;
  return op == CompareOp::Greater || op == CompareOp::GreaterEqual ? 0.0f : 1.0f;
}

bool sameDescription(const SceneDescription& a, const SceneDescription& b) {
  // Compared through their JSON, which writes every field the format has.
  return sceneToJson(a) == sceneToJson(b) && a.directory == b.directory;
}

Status parseSceneFile(const std::string& text, const std::string& name, SceneDescription& out) {
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::parse_error& e) {
    // e.byte is 1-based and points just past what could not be read.
    size_t line = 1, column = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string what = e.what();
    const size_t colon = what.rfind(": ");
    if (colon != std::string::npos) what = what.substr(colon + 2);
    return Status::error(name + ":" + std::to_string(line) + ":" + std::to_string(column) +
                         ": invalid JSON: " + what);
  }
  try {
    const std::string directory = std::filesystem::path(name).parent_path().string();
    out = readScene(Node(root, "", name), directory);
  } catch (const SceneError& e) {
    return Status::error(e.message);
  }
  return Status::ok();
}

Status loadSceneFile(const std::string& path, SceneDescription& out) {
  std::string text;
  if (Status s = readTextFile(path, text); !s) return s;
  return parseSceneFile(text, path, out);
}

std::string sceneToJson(const SceneDescription& s) {
  Json j = Json::object();
  if (!s.description.empty()) j["description"] = s.description;
  j["width"] = s.width;
  j["height"] = s.height;
  j["samples"] = s.samples;
  j["background"] = array(s.background);
  if (s.clearDepth) j["clear_depth"] = number(*s.clearDepth);
  j["camera"] = writeCamera(s.camera);
  j["lights"] = Json::array();
  for (const PointLight& l : s.lights)
    j["lights"].push_back({{"position", array(l.position)}, {"color", array(l.color)}});
  j["meshes"] = Json::object();
  for (const NamedMesh& m : s.meshes) j["meshes"][m.name] = writeMesh(m.source);
  j["draws"] = Json::array();
  for (const DrawSpec& d : s.draws)
    j["draws"].push_back({{"label", d.label},
                          {"mesh", s.meshes.at(d.mesh).name},
                          {"transform", writeTransform(d.transform)},
                          {"state", writeState(d.state)},
                          {"shader", writeShader(d.shader)}});
  if (s.animation) j["animation"] = writeAnimation(*s.animation);
  return j.dump(2) + "\n";
}

SceneDescription describeScene(const Scene& scene, const PipelineState& state, ShadingMode shading) {
  SceneDescription s;
  s.width = state.viewport.width;
  s.height = state.viewport.height;
  s.background = shading == ShadingMode::TriangleId ? glm::vec4(0, 0, 0, 1) : scene.background;
  const CompareOp op = state.depth.compare;
  s.clearDepth = op == CompareOp::Greater || op == CompareOp::GreaterEqual ? 0.0f : 1.0f;
  s.camera = scene.camera;
  s.lights.push_back({scene.lightPosition, glm::vec3(1.0f)});
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    NamedMesh m;
    m.name = "object" + std::to_string(i);
    m.source.kind = MeshSource::Kind::Inline;
    for (const MeshVertex& v : o.mesh.vertices) m.source.positions.push_back(v.position);
    m.source.indices = o.mesh.indices;
    m.mesh = o.mesh;
    s.meshes.push_back(std::move(m));
    DrawSpec d;
    d.label = s.meshes.back().name;
    d.mesh = i;
    d.transform.explicitMatrix = o.model;
    d.state = state;
    d.shader.kind = shading;
    d.shader.albedo = o.albedo;
    d.shader.color = glm::vec4(o.albedo, 1.0f);
    d.shader.depthNear = 0.9f;  // renderScene's depth shading range
    d.shader.depthFar = 1.0f;
    s.draws.push_back(std::move(d));
  }
  return s;
}

const char* compareOpName(CompareOp op) { return nameOf(kCompareOps, op); }
const char* cullModeName(CullMode mode) { return nameOf(kCullModes, mode); }
const char* frontFaceName(FrontFace face) { return nameOf(kFrontFaces, face); }
const char* shadingModeName(ShadingMode mode) { return nameOf(kShadingModes, mode); }

}  // namespace rast
