// Watertightness cases: random fans and grids of triangles with vertices on the subpixel grid,
// so that every rasterizer mode sees the same exact geometry, and the exact classification of
// each sample against their union (strictly inside, on the outline, outside). The watertightness
// tests (tests/watertight_test.cpp) draw the same generators: the same seed gives the same cases.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace rast::reference {

struct SubPoint {
  int64_t x, y;  // subpixels
};

// Twice the signed area of (a, b, c) with y down: > 0 when they run clockwise on screen.
inline int64_t orient(SubPoint a, SubPoint b, SubPoint c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

struct Mesh2D {
  std::vector<SubPoint> vertices;
  std::vector<uint32_t> indices;  // three per triangle
};

// A closed fan around a centre vertex: rim points at increasing angles, gaps below pi, so every
// triangle has the same winding and the union is star-shaped around the centre. Spokes are
// sometimes axis-aligned or end on a sample; the centre is sometimes on a sample.
Mesh2D randomFan(std::mt19937_64& rng, int64_t unit, int width, int height);

// A grid of quadrilaterals, corners jittered by up to 0.2 cells (which keeps every cell convex),
// each split along a random diagonal, each triangle with a random winding. jitter = false puts
// every corner on a sample: the most ties.
Mesh2D randomGrid(std::mt19937_64& rng, int64_t unit, int width, int height, bool jitter,
                  double cellPixels);

// Edges used by exactly one triangle: the outline of the union of a triangle set whose shared
// edges are shared by exactly two triangles.
std::vector<std::pair<uint32_t, uint32_t>> outlineEdges(const std::vector<uint32_t>& indices);

bool inClosedTriangle(const std::array<SubPoint, 3>& v, SubPoint s);
bool onSegment(SubPoint a, SubPoint b, SubPoint s);

// Per pixel of a width x height image: 1 where the centre lies in the union of the mesh's closed
// triangles and not on its outline (every watertight rasterizer covers it exactly once), else 0.
std::vector<uint8_t> strictlyInsideUnion(const Mesh2D& mesh, int64_t unit, int width, int height);

struct WatertightViolations {
  uint64_t gaps = 0;        // samples strictly inside the union that no triangle covered
  uint64_t doubleHits = 0;  // samples covered more than once (anywhere), counted once each
  uint64_t interior = 0;    // samples strictly inside the union
};

WatertightViolations countViolations(const std::vector<uint8_t>& strictlyInside,
                                     const std::vector<uint32_t>& counts);

}  // namespace rast::reference
