// A reference renderer: a ray caster, for checking the rasterizer's visibility (the verification
// method of Computer Graphics: Principles and Practice, ch. 15: render the same scene with a
// second, simple and obviously correct algorithm and compare the pictures).
//
// Everything here is double precision and unsnapped: one ray through the centre of each pixel,
// (x + 0.5, y + 0.5) in window coordinates (top-left origin, y down), built by unprojecting that
// window point at NDC depth -1 (near plane) and +1 (far plane) through the inverse of the
// camera's viewProjection. The matrices are the rasterizer's own (glm float matrices, as
// renderScene builds them with aspect = width / height), widened to double. A hit counts only
// between the near and far planes (ray parameter t in [0, 1]), as the rasterizer clips depth to
// [0, 1].
//
// Ray-triangle test: the watertight test of Woop, Benthin and Wald (JCGT 2013) in double. Edges
// are inclusive (a ray exactly on an edge hits the triangle), and an edge shared by two triangles
// gives both the same edge-function value up to sign, so no ray slips between them.
// Ties: the nearest hit wins; at exactly equal t the lower triangle id wins, which is what the
// rasterizer's CompareOp::Less gives one draw (the earlier primitive keeps the pixel).
// Triangles with a non-finite vertex are skipped, as the rasterizer drops them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/camera.h"
#include "scene/mesh.h"
#include "shaders_cpp/blinn_phong.h"

namespace rast::reference {

struct RayCastImage {
  int width = 0, height = 0;
  std::vector<int64_t> ids;   // row-major, row 0 at the top: nearest triangle, or -1
  std::vector<double> depth;  // window depth (0.5 * z/w + 0.5) of that hit, 1 where none;
                              // empty unless asked for
  int64_t id(int x, int y) const { return ids[size_t(y) * size_t(width) + size_t(x)]; }
};

// A point on a triangle's surface: position and interpolated vertex normal (not normalised),
// both from the hit's barycentric coordinates, as the rasterizer interpolates its varyings.
struct SurfacePoint {
  int64_t triangle = -1;
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};
  bool frontFacing = true;  // the triangle is counter-clockwise on the image (OpenGL's front)
};

struct RayHit {
  int64_t triangle = -1;  // -1: nothing between the near and far planes
  double t = 0;           // along the ray from the near plane (0) to the far plane (1)
  double depth = 1;       // window depth of the hit point
};

class RayCaster {
 public:
  // The mesh in world space (use flattenScene for a Scene). The camera's viewProjection is taken
  // with aspect = float(width) / float(height), as renderScene does.
  RayCaster(const Mesh& mesh, const Camera& camera, int width, int height);
  RayCaster(const Mesh& mesh, const glm::mat4& viewProjection, int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t triangleCount() const { return triangles_.size(); }

  // Every pixel: each triangle is tested only against the pixels whose centres lie in its
  // projected screen bounding box (all pixels when a vertex is behind the eye, w <= 0).
  RayCastImage render(bool withDepth = false) const;
  // One pixel against every triangle: the brute-force definition render() must agree with.
  RayHit castPixel(int x, int y) const;
  // Whether the ray through pixel (x, y) hits `triangle` between the near and far planes.
  bool hits(uint32_t triangle, int x, int y, double* t = nullptr) const;

  // The window position (x, y in pixels, z = window depth) of a world point, in double: the
  // rasterizer's viewport mapping applied to viewProjection * p without its float rounding.
  // `w` receives the clip-space w (the projection means nothing where w <= 0).
  glm::dvec3 toWindow(const glm::dvec3& world, double* w = nullptr) const;

  // The triangle's vertices projected by toWindow. inFront: all three have w > 0, so the
  // projected triangle is the triangle's image and the functions below are meaningful.
  struct Projected {
    std::array<glm::dvec3, 3> window;
    bool inFront = false;
  };
  const Projected& projected(uint32_t triangle) const { return projected_[triangle]; }

  // Distance in pixels from the centre of pixel (x, y) to the nearest of the triangle's three
  // projected edges (segments, unsnapped). Infinity unless the triangle is inFront.
  double edgeDistance(uint32_t triangle, int x, int y) const;
  // Distance in pixels from the centre of pixel (x, y) to the edges clipping adds where the
  // triangle crosses the near plane (window depth 0) or the far plane (1): the segment of the
  // projected triangle along which its depth plane equals 0 or 1. Infinity where it crosses
  // neither, or unless inFront.
  double depthClipEdgeDistance(uint32_t triangle, int x, int y) const;
  // The window depth of the triangle's plane at window point (x, y): z/w is affine in window
  // coordinates, so it is the plane through the three projected (x, y, z). Its gradient, per
  // pixel, is depthGradient. Both NaN unless inFront (or for a triangle projecting to a line).
  double windowDepth(uint32_t triangle, double x, double y) const;
  glm::dvec2 depthGradient(uint32_t triangle) const;

  // ---- Shading (Blinn-Phong with shadow rays, the formula of shaders_cpp/blinn_phong.h) ----

  // Where the ray through window point (wx, wy) meets the plane of `triangle`, extended beyond
  // its edges (barycentrics may be negative): the surface a rasterizer's interpolation sees at
  // that point. False where the ray is parallel to the plane.
  bool surfaceAt(uint32_t triangle, double wx, double wy, SurfacePoint& out) const;
  // Whether any triangle other than `ignore` crosses the open segment from `from` towards the
  // light (to the point light, or 2x the mesh's extent against a directional light's direction).
  bool occluded(const glm::dvec3& from, const Light& light, int64_t ignore) const;
  // The Blinn-Phong colour of a surface point seen from `eye`, lit (visibility 1) or shadowed (0).
  static glm::dvec3 shadeBlinnPhong(const SurfacePoint& p, const BlinnPhongMaterial& material,
                                    const Light& light, const glm::dvec3& eye, double visibility);

 private:
  struct Ray {
    glm::dvec3 origin, direction;  // origin on the near plane; origin + direction on the far plane
    int kx, ky, kz;                // axis permutation of the watertight test
    double sx, sy, sz;             // shear constants
  };
  Ray rayThrough(int x, int y) const { return rayThroughPoint(x + 0.5, y + 0.5); }
  Ray rayThroughPoint(double wx, double wy) const;
  static Ray makeRay(const glm::dvec3& origin, const glm::dvec3& direction);
  // Watertight test; on a hit writes t in [tMin, 1] (and the barycentrics, if asked).
  static bool intersect(const Ray& ray, const std::array<glm::dvec3, 3>& v, double& t,
                        double tMin = 0.0, glm::dvec3* barycentric = nullptr);

  int width_, height_;
  glm::dmat4 viewProjection_, inverseViewProjection_;
  std::vector<std::array<glm::dvec3, 3>> triangles_;  // world space
  std::vector<std::array<glm::dvec3, 3>> normals_;    // the vertices' normals
  std::vector<std::array<glm::dvec3, 2>> bounds_;     // world-space box of each triangle
  double extent_ = 0;                                 // diagonal of the mesh's box
  std::vector<Projected> projected_;
  std::vector<bool> finite_;
};

}  // namespace rast::reference
