#include "reference/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace rast::reference {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

double pointSegmentDistance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double s = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + s * ab));
}

}  // namespace

RayCaster::RayCaster(const Mesh& mesh, const Camera& camera, int width, int height)
    : RayCaster(mesh, camera.viewProjection(float(width) / float(height)), width, height) {}

RayCaster::RayCaster(const Mesh& mesh, const glm::mat4& viewProjection, int width, int height)
    : width_(width),
      height_(height),
      viewProjection_(viewProjection),
      inverseViewProjection_(glm::inverse(glm::dmat4(viewProjection))) {
  const size_t count = mesh.triangleCount();
  triangles_.resize(count);
  normals_.resize(count);
  bounds_.resize(count);
  glm::dvec3 meshMin(kInfinity), meshMax(-kInfinity);
  projected_.resize(count);
  finite_.resize(count);
  for (size_t t = 0; t < count; ++t) {
    bool finite = true, inFront = true;
    for (int k = 0; k < 3; ++k) {
      const MeshVertex& vertex = mesh.vertices[mesh.indices[3 * t + k]];
      const glm::dvec3 p(vertex.position);
      triangles_[t][k] = p;
      normals_[t][k] = glm::dvec3(vertex.normal);
      finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      double w = 0;
      projected_[t].window[k] = toWindow(p, &w);
      inFront = inFront && w > 0;
    }
    finite_[t] = finite;
    bounds_[t] = {glm::min(glm::min(triangles_[t][0], triangles_[t][1]), triangles_[t][2]),
                  glm::max(glm::max(triangles_[t][0], triangles_[t][1]), triangles_[t][2])};
    if (finite) {
      meshMin = glm::min(meshMin, bounds_[t][0]);
      meshMax = glm::max(meshMax, bounds_[t][1]);
    }
    projected_[t].inFront = finite && inFront;
  }
  extent_ = count > 0 && meshMin.x <= meshMax.x ? glm::length(meshMax - meshMin) : 0.0;
}

glm::dvec3 RayCaster::toWindow(const glm::dvec3& world, double* w) const {
  const glm::dvec4 clip = viewProjection_ * glm::dvec4(world, 1.0);
  if (w) *w = clip.w;
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  // ScreenMapping::forState for the viewport (0, 0, width, height): y flipped, depth to [0, 1].
  return {ndc.x * (0.5 * width_) + 0.5 * width_, ndc.y * (-0.5 * height_) + 0.5 * height_,
          ndc.z * 0.5 + 0.5};
}

RayCaster::Ray RayCaster::rayThroughPoint(double wx, double wy) const {
  const double ndcX = (wx - 0.5 * width_) / (0.5 * width_);
  const double ndcY = (wy - 0.5 * height_) / (-0.5 * height_);
  auto unproject = [&](double ndcZ) {
    const glm::dvec4 p = inverseViewProjection_ * glm::dvec4(ndcX, ndcY, ndcZ, 1.0);
    return glm::dvec3(p) / p.w;
  };
  const glm::dvec3 origin = unproject(-1.0);
  return makeRay(origin, unproject(1.0) - origin);
}

RayCaster::Ray RayCaster::makeRay(const glm::dvec3& origin, const glm::dvec3& direction) {
  Ray ray;
  ray.origin = origin;
  ray.direction = direction;
  // Woop et al.: kz is the dominant axis of the direction; kx, ky the others, swapped so the
  // winding is kept when the direction points down kz.
  const glm::dvec3 a = glm::abs(ray.direction);
  ray.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  ray.kx = (ray.kz + 1) % 3;
  ray.ky = (ray.kx + 1) % 3;
  if (ray.direction[ray.kz] < 0) std::swap(ray.kx, ray.ky);
  ray.sx = ray.direction[ray.kx] / ray.direction[ray.kz];
  ray.sy = ray.direction[ray.ky] / ray.direction[ray.kz];
  ray.sz = 1.0 / ray.direction[ray.kz];
  return ray;
}

bool RayCaster::intersect(const Ray& r, const std::array<glm::dvec3, 3>& v, double& t,
                          double tMin, glm::dvec3* barycentric) {
  // Vertices relative to the ray origin, sheared so the ray runs along +z through (0, 0).
  const glm::dvec3 a = v[0] - r.origin, b = v[1] - r.origin, c = v[2] - r.origin;
  const double ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const double bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const double cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
  // 2D edge functions at the origin. The edge (p, q) is always evaluated as qx*py - qy*px of the
  // same sheared vertices, so the neighbour across a shared edge gets exactly the negated value.
  const double u = cx * by - cy * bx;
  const double vv = ax * cy - ay * cx;
  const double w = bx * ay - by * ax;
  if ((u < 0 || vv < 0 || w < 0) && (u > 0 || vv > 0 || w > 0)) return false;  // inclusive edges
  const double det = u + vv + w;
  if (det == 0) return false;  // the ray lies in the triangle's plane, or it is degenerate
  const double az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  const double tt = (u * az + vv * bz + w * cz) / det;
  if (!(tt >= tMin && tt <= 1.0)) return false;  // before the near or beyond the far plane
  t = tt;
  if (barycentric) *barycentric = glm::dvec3(u, vv, w) / det;
  return true;
}

bool RayCaster::hits(uint32_t triangle, int x, int y, double* t) const {
  if (!finite_[triangle]) return false;
  double tt;
  if (!intersect(rayThrough(x, y), triangles_[triangle], tt)) return false;
  if (t) *t = tt;
  return true;
}

RayHit RayCaster::castPixel(int x, int y) const {
  const Ray ray = rayThrough(x, y);
  RayHit best;
  double bestT = kInfinity;
  for (uint32_t i = 0; i < triangles_.size(); ++i) {
    double t;
    // Strictly nearer: at equal t the lower id, met first, keeps the pixel.
    if (finite_[i] && intersect(ray, triangles_[i], t) && t < bestT) {
      bestT = t;
      best.triangle = i;
    }
  }
  if (best.triangle >= 0) {
    best.t = bestT;
    best.depth = toWindow(ray.origin + bestT * ray.direction).z;
  }
  return best;
}

RayCastImage RayCaster::render(bool withDepth) const {
  const size_t pixels = size_t(width_) * size_t(height_);
  std::vector<Ray> rays(pixels);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) rays[size_t(y) * width_ + x] = rayThrough(x, y);

  RayCastImage image;
  image.width = width_;
  image.height = height_;
  image.ids.assign(pixels, -1);
  std::vector<double> bestT(pixels, kInfinity);
  // A ray that hits a triangle passes through its projection, so its pixel centre lies in the
  // projected bounding box up to rounding (~1e-12 px here); kPad covers that generously.
  constexpr double kPad = 1e-3;
  for (uint32_t i = 0; i < triangles_.size(); ++i) {
    if (!finite_[i]) continue;
    int x0 = 0, y0 = 0, x1 = width_ - 1, y1 = height_ - 1;
    const Projected& p = projected_[i];
    if (p.inFront) {
      double minX = kInfinity, minY = kInfinity, maxX = -kInfinity, maxY = -kInfinity;
      for (const glm::dvec3& v : p.window) {
        minX = std::min(minX, v.x);
        maxX = std::max(maxX, v.x);
        minY = std::min(minY, v.y);
        maxY = std::max(maxY, v.y);
      }
      // Pixels whose centre x + 0.5 lies in [minX - kPad, maxX + kPad], clamped to the image.
      auto first = [](double lo, int limit) {
        return int(std::clamp(std::ceil(lo - kPad - 0.5), 0.0, double(limit)));
      };
      auto last = [](double hi, int limit) {
        return int(std::clamp(std::floor(hi + kPad - 0.5), -1.0, double(limit - 1)));
      };
      x0 = first(minX, width_);
      x1 = last(maxX, width_);
      y0 = first(minY, height_);
      y1 = last(maxY, height_);
    }
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const size_t k = size_t(y) * width_ + x;
        double t;
        // Triangles go in id order, so at equal t the lower id keeps the pixel, as in castPixel.
        if (intersect(rays[k], triangles_[i], t) && t < bestT[k]) {
          bestT[k] = t;
          image.ids[k] = i;
        }
      }
  }
  if (withDepth) {
    image.depth.assign(pixels, 1.0);
    for (size_t k = 0; k < pixels; ++k)
      if (image.ids[k] >= 0)
        image.depth[k] = toWindow(rays[k].origin + bestT[k] * rays[k].direction).z;
  }
  return image;
}

double RayCaster::edgeDistance(uint32_t triangle, int x, int y) const {
  const Projected& p = projected_[triangle];
  if (!p.inFront) return kInfinity;
  const glm::dvec2 c(x + 0.5, y + 0.5);
  double d = kInfinity;
  for (int k = 0; k < 3; ++k)
    d = std::min(d, pointSegmentDistance(c, glm::dvec2(p.window[k]),
                                         glm::dvec2(p.window[(k + 1) % 3])));
  return d;
}

double RayCaster::depthClipEdgeDistance(uint32_t triangle, int x, int y) const {
  const Projected& p = projected_[triangle];
  if (!p.inFront) return kInfinity;
  const glm::dvec2 c(x + 0.5, y + 0.5);
  double d = kInfinity;
  for (const double plane : {0.0, 1.0}) {
    // Where the edges cross depth == plane (depth is linear along a projected edge).
    glm::dvec2 ends[3];
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 &a = p.window[k], &b = p.window[(k + 1) % 3];
      const double da = a.z - plane, db = b.z - plane;
      if ((da < 0) != (db < 0)) ends[count++] = glm::dvec2(a) + da / (da - db) * glm::dvec2(b - a);
    }
    if (count == 2) d = std::min(d, pointSegmentDistance(c, ends[0], ends[1]));
  }
  return d;
}

glm::dvec2 RayCaster::depthGradient(uint32_t triangle) const {
  const Projected& p = projected_[triangle];
  if (!p.inFront) return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
  const glm::dvec3 n = glm::cross(p.window[1] - p.window[0], p.window[2] - p.window[0]);
  return {-n.x / n.z, -n.y / n.z};
}

double RayCaster::windowDepth(uint32_t triangle, double x, double y) const {
  const glm::dvec2 g = depthGradient(triangle);
  const glm::dvec3& v0 = projected_[triangle].window[0];
  return v0.z + g.x * (x - v0.x) + g.y * (y - v0.y);
}

}  // namespace rast::reference

namespace rast::reference {

bool RayCaster::surfaceAt(uint32_t triangle, double wx, double wy, SurfacePoint& out) const {
  const Ray ray = rayThroughPoint(wx, wy);
  const std::array<glm::dvec3, 3>& v = triangles_[triangle];
  const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
  const double denom = glm::dot(n, ray.direction);
  if (denom == 0 || !finite_[triangle]) return false;
  const glm::dvec3 p = ray.origin + ray.direction * (glm::dot(n, v[0] - ray.origin) / denom);
  // Barycentrics of p in the plane, by areas against the full normal (signed, so they extend
  // past the edges linearly).
  const double n2 = glm::dot(n, n);
  const double b0 = glm::dot(n, glm::cross(v[1] - p, v[2] - p)) / n2;
  const double b1 = glm::dot(n, glm::cross(v[2] - p, v[0] - p)) / n2;
  const double b2 = 1.0 - b0 - b1;
  out.triangle = triangle;
  out.position = p;
  out.normal = b0 * normals_[triangle][0] + b1 * normals_[triangle][1] + b2 * normals_[triangle][2];
  // Counter-clockwise on the image (y down): the projected signed area is negative.
  const Projected& pr = projected_[triangle];
  const glm::dvec3 e1 = pr.window[1] - pr.window[0], e2 = pr.window[2] - pr.window[0];
  out.frontFacing = e1.x * e2.y - e1.y * e2.x < 0;
  return true;
}

bool RayCaster::occluded(const glm::dvec3& from, const Light& light, int64_t ignore) const {
  const glm::dvec3 direction = light.kind == Light::Kind::Point
                                   ? glm::dvec3(light.position) - from
                                   : -glm::normalize(glm::dvec3(light.direction)) * (2.0 * extent_);
  const Ray ray = makeRay(from, direction);
  const glm::dvec3 lo = glm::min(from, from + direction), hi = glm::max(from, from + direction);
  // Hits closer than 1e-9 of the segment are the surface the ray leaves (a neighbour sharing
  // the point's edge), not an occluder.
  constexpr double kMinT = 1e-9;
  for (uint32_t i = 0; i < triangles_.size(); ++i) {
    if (int64_t(i) == ignore || !finite_[i]) continue;
    const auto& b = bounds_[i];
    if (b[1].x < lo.x || b[0].x > hi.x || b[1].y < lo.y || b[0].y > hi.y || b[1].z < lo.z ||
        b[0].z > hi.z)
      continue;
    double t;
    if (intersect(ray, triangles_[i], t, kMinT)) return true;
  }
  return false;
}

glm::dvec3 RayCaster::shadeBlinnPhong(const SurfacePoint& p, const BlinnPhongMaterial& material,
                                      const Light& light, const glm::dvec3& eye,
                                      double visibility) {
  glm::dvec3 n = glm::normalize(p.normal);
  if (!p.frontFacing) n = -n;
  const glm::dvec3 l = light.kind == Light::Kind::Point
                           ? glm::normalize(glm::dvec3(light.position) - p.position)
                           : -glm::dvec3(light.direction);
  const glm::dvec3 h = glm::normalize(l + glm::normalize(eye - p.position));
  const double diffuse = std::max(glm::dot(n, l), 0.0);
  const double specular =
      diffuse > 0 ? std::pow(std::max(glm::dot(n, h), 0.0), double(material.shininess)) : 0.0;
  const glm::dvec3 albedo(material.albedo);
  return glm::dvec3(light.ambient) * albedo +
         visibility * glm::dvec3(light.color) * (albedo * diffuse + glm::dvec3(material.specular) * specular);
}

}  // namespace rast::reference
