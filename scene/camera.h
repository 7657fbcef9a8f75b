// A perspective camera (OpenGL conventions) and framing of a bounding box.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace rast {

struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYDegrees = 45.0f;
  float nearPlane = 0.1f;
  float farPlane = 100.0f;

  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
  glm::mat4 viewProjection(float aspect) const { return projection(aspect) * view(); }
};

// The benchmark workloads' framing of a sphere (centre, radius): eye on +z at
// distance r / sin(fov/2) * 1.02 looking down -z at the centre, near =
// max(dist - 1.5 r, 0.01 dist), far = dist + 1.5 r.
Camera frameSphere(glm::vec3 centre, float radius, float fovYDegrees = 45.0f);

struct Mesh;
// frameSphere around the mesh: centre of its bounding box, radius the farthest vertex from it.
Camera frameMesh(const Mesh& mesh, float fovYDegrees = 45.0f);

}  // namespace rast
