// Blinn-Phong shading with one light (directional or point) and an optional shadow map.
//
//   colour = ambient * albedo + visibility * lightColor * (albedo * max(n.l, 0) + specular * s)
//   s = max(n.h, 0)^shininess where n.l > 0, else 0;  h = normalize(l + v)
// n is the interpolated normal (flipped on back faces, so open meshes are lit from both sides),
// l the unit vector towards the light, v towards the eye. reference/ray_caster.h evaluates the
// same formula in double with shadow rays.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "pipeline/shader.h"
#include "pipeline/shadow_map.h"
#include "shaders_cpp/mesh_vertex.h"

namespace rast {

struct Light {
  enum class Kind { Directional, Point };
  Kind kind = Kind::Point;
  glm::vec3 position{0.0f, 10.0f, 10.0f};  // Point
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // Directional: the way the light travels (unit)
  glm::vec3 color{1.0f};
  glm::vec3 ambient{0.08f};

  // Unit vector from `p` towards the light.
  glm::vec3 towards(glm::vec3 p) const {
    return kind == Kind::Point ? glm::normalize(position - p) : -direction;
  }
};

struct BlinnPhongMaterial {
  glm::vec3 albedo{0.8f};
  glm::vec3 specular{0.3f};
  float shininess = 32.0f;
};

// World normal (varyings 0..2), world position (3..5) and the light-space clip position (6..9).
// The latter is taken at the position pushed `normalOffset` world units along the normal: the
// usual normal-offset bias, which moves the lookup off the receiver's own surface where the
// light grazes it (0 turns it off).
struct ShadowVertexShader {
  using Vertex = MeshVertex;
  static constexpr int kVaryings = 10;
  glm::mat4 model{1.0f};
  glm::mat4 viewProjection{1.0f};
  glm::mat4 lightViewProjection{1.0f};
  float normalOffset = 0.0f;

  ShadedVertex<10> operator()(const Vertex& v) const {
    const glm::vec4 world = model * glm::vec4(v.position, 1.0f);
    const glm::vec3 n = glm::mat3(model) * v.normal;  // rigid or uniformly scaled models
    const glm::vec3 offset = normalOffset != 0.0f ? glm::normalize(n) * normalOffset : glm::vec3(0);
    const glm::vec4 light = lightViewProjection * (world + glm::vec4(offset, 0.0f));
    return {viewProjection * world,
            {n.x, n.y, n.z, world.x, world.y, world.z, light.x, light.y, light.z, light.w}};
  }
};

struct BlinnPhongShader {
  static constexpr int kVaryings = 10;
  static constexpr bool kMayDiscard = false;
  BlinnPhongMaterial material;
  Light light;
  glm::vec3 eye{0.0f};
  ShadowMap shadowMap;  // no depth plane: no shadows
  float depthBias = 0.0f;
  int pcf = 1;

  glm::vec3 shade(const Fragment<10>& f, float visibility) const {
    glm::vec3 n = glm::normalize(glm::vec3(f.varyings[0], f.varyings[1], f.varyings[2]));
    if (!f.frontFacing) n = -n;
    const glm::vec3 p(f.varyings[3], f.varyings[4], f.varyings[5]);
    const glm::vec3 l = light.towards(p);
    const glm::vec3 h = glm::normalize(l + glm::normalize(eye - p));
    const float diffuse = std::max(glm::dot(n, l), 0.0f);
    const float specular =
        diffuse > 0.0f ? std::pow(std::max(glm::dot(n, h), 0.0f), material.shininess) : 0.0f;
    return light.ambient * material.albedo +
           visibility * light.color * (material.albedo * diffuse + material.specular * specular);
  }

  float visibility(const Fragment<10>& f) const {
    if (!shadowMap.depth) return 1.0f;
    return shadowMap.visibility(
        glm::vec4(f.varyings[6], f.varyings[7], f.varyings[8], f.varyings[9]), depthBias, pcf);
  }

  PixelResult operator()(const Fragment<10>& f) const {
    return {glm::vec4(shade(f, visibility(f)), 1.0f)};
  }
};

// The shadow lookup alone, as grey (1 lit, 0 shadowed): for tests and pictures of the map.
struct ShadowVisibilityShader {
  static constexpr int kVaryings = 10;
  static constexpr bool kMayDiscard = false;
  ShadowMap shadowMap;
  float depthBias = 0.0f;
  int pcf = 1;

  PixelResult operator()(const Fragment<10>& f) const {
    const float v = shadowMap.visibility(
        glm::vec4(f.varyings[6], f.varyings[7], f.varyings[8], f.varyings[9]), depthBias, pcf);
    return {glm::vec4(v, v, v, 1.0f)};
  }
};

}  // namespace rast
