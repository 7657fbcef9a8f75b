// Camera animation over a sequence of frames: an orbit about an axis, or a linear path through
// keyframes.
#pragma once

#include <variant>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/camera.h"

namespace rast {

// Frame f of N turns the camera (eye, target and up) by degrees * f / N about the axis through
// `centre`, so a full turn does not repeat its first frame.
struct OrbitAnimation {
  glm::vec3 centre{0.0f};
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
  float degrees = 360.0f;
  friend bool operator==(const OrbitAnimation&, const OrbitAnimation&) = default;
};

struct CameraKeyframe {
  int frame = 0;
  glm::vec3 eye{0.0f};
  glm::vec3 target{0.0f};
  friend bool operator==(const CameraKeyframe&, const CameraKeyframe&) = default;
};

// Eye and target move linearly between keyframes (frames strictly increasing) and hold before
// the first and after the last.
struct PathAnimation {
  std::vector<CameraKeyframe> keyframes;
  friend bool operator==(const PathAnimation&, const PathAnimation&) = default;
};

struct CameraAnimation {
  int frames = 1;
  std::variant<OrbitAnimation, PathAnimation> motion;
  friend bool operator==(const CameraAnimation&, const CameraAnimation&) = default;
};

// The camera of frame `frame` (0-based) of `animation`, starting from `base`.
Camera cameraAtFrame(const Camera& base, const CameraAnimation& animation, int frame);

}  // namespace rast
