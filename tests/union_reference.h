// A test reference shared by the clipping and watertightness tests.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "pipeline/state.h"

namespace rast::test_support {

// Reference: the union of clip-space triangles, clipped in double against w >= 0, the near and
// the far plane, projected with the viewport transform. A sample is classified as inside (1),
// outside (0) or unknown (-1) when it lies within `margin` pixels of the union's outline: the
// triangles' edges that are not shared with another triangle, and the edges the clipper makes.
class UnionReference {
 public:
  explicit UnionReference(Viewport vp) : vp_(vp) {}

  // boundary[k]: edge v[k] -> v[k+1] is on the outline of the union (not shared).
  void addTriangle(const std::array<glm::dvec4, 3>& v, std::array<bool, 3> boundary) {
    struct PV {
      glm::dvec4 p;
      bool edgeOnOutline;  // the edge from this vertex to the next
    };
    std::vector<PV> poly = {{v[0], boundary[0]}, {v[1], boundary[1]}, {v[2], boundary[2]}};
    const std::array<glm::dvec4, 3> planes = {glm::dvec4(0, 0, 0, 1), glm::dvec4(0, 0, 1, 1),
                                              glm::dvec4(0, 0, -1, 1)};
    for (const glm::dvec4& plane : planes) {
      std::vector<PV> out;
      for (size_t i = 0; i < poly.size(); ++i) {
        const PV& cur = poly[i];
        const PV& next = poly[(i + 1) % poly.size()];
        const double dc = glm::dot(plane, cur.p), dn = glm::dot(plane, next.p);
        auto cut = [&] { return cur.p + (dc / (dc - dn)) * (next.p - cur.p); };
        if (dc >= 0) {
          out.push_back(cur);
          // From where the edge leaves to where the outline comes back runs along the plane.
          if (dn < 0) out.push_back({cut(), true});
        } else if (dn >= 0) {
          out.push_back({cut(), cur.edgeOnOutline});
        }
      }
      poly = std::move(out);
      if (poly.size() < 3) return;
    }
    Polygon projected;
    for (const PV& q : poly) {
      const glm::dvec2 w = project(q.p);
      projected.pts.push_back(w);
      projected.outline.push_back(q.edgeOnOutline);
    }
    polygons_.push_back(std::move(projected));
  }

  glm::dvec2 project(const glm::dvec4& p) const {
    return {p.x / p.w * 0.5 * vp_.width + vp_.x + 0.5 * vp_.width,
            -p.y / p.w * 0.5 * vp_.height + vp_.y + 0.5 * vp_.height};
  }

  int classify(double x, double y, double margin) const {
    bool inside = false;
    double dist = std::numeric_limits<double>::infinity();
    const glm::dvec2 s(x, y);
    for (const Polygon& p : polygons_) {
      bool pos = true, neg = true;
      for (size_t i = 0; i < p.pts.size(); ++i) {
        const glm::dvec2 a = p.pts[i], b = p.pts[(i + 1) % p.pts.size()];
        const double c = (b.x - a.x) * (s.y - a.y) - (b.y - a.y) * (s.x - a.x);
        pos &= c >= 0;
        neg &= c <= 0;
        if (p.outline[i]) dist = std::min(dist, segmentDistance(s, a, b));
      }
      inside |= pos || neg;
    }
    if (dist <= margin) return -1;
    return inside ? 1 : 0;
  }

 private:
  struct Polygon {
    std::vector<glm::dvec2> pts;
    std::vector<bool> outline;
  };
  static double segmentDistance(glm::dvec2 s, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(glm::dot(s - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(s - (a + t * ab));
  }
  Viewport vp_;
  std::vector<Polygon> polygons_;
};

}  // namespace rast::test_support
