#include "scene/animation.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace rast {
namespace {

Camera orbit(const Camera& base, const OrbitAnimation& o, int frame, int frames) {
  const double degrees = double(o.degrees) * frame / frames;
  const glm::mat4 turn =
      glm::rotate(glm::mat4(1.0f), glm::radians(float(degrees)), glm::normalize(o.axis));
  auto around = [&](glm::vec3 p) { return o.centre + glm::vec3(turn * glm::vec4(p - o.centre, 0.0f)); };
  Camera c = base;
  c.eye = around(base.eye);
  c.target = around(base.target);
  c.up = glm::vec3(turn * glm::vec4(base.up, 0.0f));
  return c;
}

Camera path(const Camera& base, const PathAnimation& p, int frame) {
  Camera c = base;
  const std::vector<CameraKeyframe>& k = p.keyframes;
  if (k.empty()) return c;
  if (frame <= k.front().frame) {
    c.eye = k.front().eye;
    c.target = k.front().target;
    return c;
  }
  for (size_t i = 1; i < k.size(); ++i) {
    if (frame <= k[i].frame) {
      const float t = float(frame - k[i - 1].frame) / float(k[i].frame - k[i - 1].frame);
      c.eye = glm::mix(k[i - 1].eye, k[i].eye, t);
      c.target = glm::mix(k[i - 1].target, k[i].target, t);
      return c;
    }
  }
  c.eye = k.back().eye;
  c.target = k.back().target;
  return c;
}

}  // namespace

Camera cameraAtFrame(const Camera& base, const CameraAnimation& animation, int frame) {
  if (const auto* o = std::get_if<OrbitAnimation>(&animation.motion))
    return orbit(base, *o, frame, animation.frames);
  return path(base, std::get<PathAnimation>(animation.motion), frame);
}

}  // namespace rast
