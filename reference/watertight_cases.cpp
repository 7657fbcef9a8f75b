#include "reference/watertight_cases.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace rast::reference {

Mesh2D randomFan(std::mt19937_64& rng, int64_t unit, int width, int height) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (;;) {
    Mesh2D m;
    const int n = 5 + int(rng() % 12);
    SubPoint c{int64_t((8 + u(rng) * (width - 16)) * unit),
               int64_t((8 + u(rng) * (height - 16)) * unit)};
    if (rng() % 2) c = {c.x / unit * unit + unit / 2, c.y / unit * unit + unit / 2};  // on a sample
    m.vertices.push_back(c);
    const double start = u(rng) * 6.283185307179586;
    for (int k = 0; k < n; ++k) {
      const double angle = start + (k + 0.8 * (u(rng) - 0.5)) * 6.283185307179586 / n;
      const double radius = (0.5 + u(rng) * 30.0) * unit;
      SubPoint p{c.x + std::llround(radius * std::cos(angle)),
                 c.y + std::llround(radius * std::sin(angle))};
      switch (rng() % 6) {  // spokes through samples, and axis-aligned spokes
        case 0:
          p = {p.x / unit * unit + unit / 2, p.y / unit * unit + unit / 2};
          break;
        case 1:
          p.x = c.x;
          break;
        case 2:
          p.y = c.y;
          break;
        default:
          break;
      }
      m.vertices.push_back(p);
    }
    bool ok = true;
    for (int k = 0; k < n; ++k) {
      const uint32_t a = 1 + k, b = 1 + (k + 1) % n;
      // Increasing angles with y down run clockwise on screen (orient > 0): one winding for all,
      // which the axis-aligned and on-sample moves above must not have broken.
      ok &= orient(m.vertices[0], m.vertices[a], m.vertices[b]) > 0;
      if (rng() % 2)
        m.indices.insert(m.indices.end(), {0, a, b});
      else
        m.indices.insert(m.indices.end(), {b, a, 0});  // the other winding: same coverage
    }
    if (ok) return m;
  }
}

Mesh2D randomGrid(std::mt19937_64& rng, int64_t unit, int width, int height, bool jitter,
                  double cellPixels) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Mesh2D m;
  // On samples, cells are whole pixels so that no two corners meet.
  const int64_t cell = jitter ? std::max<int64_t>(3, std::llround(cellPixels * unit))
                              : std::max<int64_t>(1, std::llround(cellPixels)) * unit;
  const int nx = std::max<int>(2, std::min<int64_t>(12, (width - 4) * unit / cell));
  const int ny = std::max<int>(2, std::min<int64_t>(12, (height - 4) * unit / cell));
  int64_t ox = int64_t(u(rng) * (width * unit - nx * cell)),
          oy = int64_t(u(rng) * (height * unit - ny * cell));
  if (!jitter) ox = ox / unit * unit + unit / 2, oy = oy / unit * unit + unit / 2;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      SubPoint p{ox + i * cell, oy + j * cell};
      if (jitter) {
        p.x += std::llround((u(rng) - 0.5) * 0.4 * cell);
        p.y += std::llround((u(rng) - 0.5) * 0.4 * cell);
      }
      m.vertices.push_back(p);
    }
  auto id = [&](int i, int j) { return uint32_t(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      std::array<std::array<uint32_t, 3>, 2> tris =
          rng() % 2 ? std::array<std::array<uint32_t, 3>, 2>{{{a, b, c}, {a, c, d}}}
                    : std::array<std::array<uint32_t, 3>, 2>{{{a, b, d}, {b, c, d}}};
      for (auto& t : tris) {
        if (rng() % 2) std::swap(t[1], t[2]);
        m.indices.insert(m.indices.end(), t.begin(), t.end());
      }
    }
  return m;
}

std::vector<std::pair<uint32_t, uint32_t>> outlineEdges(const std::vector<uint32_t>& indices) {
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (const auto& [edge, n] : uses)
    if (n == 1) out.push_back(edge);
  return out;
}

bool inClosedTriangle(const std::array<SubPoint, 3>& v, SubPoint s) {
  const int64_t o = orient(v[0], v[1], v[2]);
  if (o == 0) return false;
  for (int i = 0; i < 3; ++i) {
    const int64_t e = orient(v[i], v[(i + 1) % 3], s);
    if (e != 0 && (e > 0) != (o > 0)) return false;
  }
  return true;
}

bool onSegment(SubPoint a, SubPoint b, SubPoint s) {
  return orient(a, b, s) == 0 && s.x >= std::min(a.x, b.x) && s.x <= std::max(a.x, b.x) &&
         s.y >= std::min(a.y, b.y) && s.y <= std::max(a.y, b.y);
}

std::vector<uint8_t> strictlyInsideUnion(const Mesh2D& m, int64_t unit, int width, int height) {
  auto sample = [&](int x, int y) { return SubPoint{x * unit + unit / 2, y * unit + unit / 2}; };
  // Pixels whose centres may lie in [lo, hi] subpixels, clamped to the image.
  auto pixelRange = [&](int64_t lo, int64_t hi, int limit) {
    const int a = int(std::clamp<int64_t>(lo / unit - 1, 0, limit));
    const int b = int(std::clamp<int64_t>(hi / unit + 2, 0, limit));
    return std::pair<int, int>(a, b);
  };
  std::vector<uint8_t> inUnion(size_t(width) * height, 0), onOutline(size_t(width) * height, 0);
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::array<SubPoint, 3> v = {m.vertices[m.indices[t]], m.vertices[m.indices[t + 1]],
                                       m.vertices[m.indices[t + 2]]};
    const auto [x0, x1] =
        pixelRange(std::min({v[0].x, v[1].x, v[2].x}), std::max({v[0].x, v[1].x, v[2].x}), width);
    const auto [y0, y1] =
        pixelRange(std::min({v[0].y, v[1].y, v[2].y}), std::max({v[0].y, v[1].y, v[2].y}), height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) inUnion[size_t(y) * width + x] |= inClosedTriangle(v, sample(x, y));
  }
  for (const auto& [a, b] : outlineEdges(m.indices)) {
    const SubPoint p = m.vertices[a], q = m.vertices[b];
    const auto [x0, x1] = pixelRange(std::min(p.x, q.x), std::max(p.x, q.x), width);
    const auto [y0, y1] = pixelRange(std::min(p.y, q.y), std::max(p.y, q.y), height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) onOutline[size_t(y) * width + x] |= onSegment(p, q, sample(x, y));
  }
  for (size_t i = 0; i < inUnion.size(); ++i) inUnion[i] &= !onOutline[i];
  return inUnion;
}

WatertightViolations countViolations(const std::vector<uint8_t>& strictlyInside,
                                     const std::vector<uint32_t>& counts) {
  WatertightViolations v;
  for (size_t i = 0; i < counts.size(); ++i) {
    v.interior += strictlyInside[i];
    v.gaps += strictlyInside[i] && counts[i] == 0;
    v.doubleHits += counts[i] > 1;
  }
  return v;
}

}  // namespace rast::reference
