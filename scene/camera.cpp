#include "scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/mesh.h"

namespace rast {

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projection(float aspect) const {
  return glm::perspective(glm::radians(fovYDegrees), aspect, nearPlane, farPlane);
}

Camera frameSphere(glm::vec3 centre, float radius, float fovYDegrees) {
  Camera c;
  const float dist = radius / std::sin(glm::radians(fovYDegrees * 0.5f)) * 1.02f;
  c.target = centre;
  c.eye = centre + glm::vec3(0.0f, 0.0f, dist);
  c.fovYDegrees = fovYDegrees;
  c.nearPlane = std::max(dist - 1.5f * radius, 0.01f * dist);
  c.farPlane = dist + 1.5f * radius;
  return c;
}

Camera frameMesh(const Mesh& mesh, float fovYDegrees) {
  const glm::vec3 centre = (mesh.boundsMin() + mesh.boundsMax()) * 0.5f;
  float radius = 0.0f;
  for (const MeshVertex& v : mesh.vertices) radius = std::max(radius, glm::distance(v.position, centre));
  return frameSphere(centre, radius, fovYDegrees);
}

}  // namespace rast
