// coverageScalar, classifyTile, rectMask and the bounds of setupCoverage against a brute-force
// reference written here from the definitions, on tens of thousands of seeded random triangles.
//
// The reference does not use EdgeFunction or the library's orientation handling: per edge p-q
// with opposite vertex r it takes the exact (__int128) cross products of the sample and of r with
// the edge, covers a sample strictly on r's side, and decides a sample exactly on the edge by
// looking at where r lies: top edge = horizontal with r below, left edge = r at larger x than the
// edge line at r's height. This is the top-left rule as D3D states it, independent of the winding.
#include "rasterizer/coverage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "rasterizer/edge_function.h"
#include "rasterizer/fixed_point.h"
#include "rasterizer/pixel_rect.h"
#include "rasterizer/triangle_setup.h"

namespace rast {
namespace {

using i128 = __int128;
using Tri = std::array<SnappedPoint, 3>;

const FixedPointFormat kFormats[] = {FixedPointFormat::d24_4(), FixedPointFormat::d16_8()};

int sign(i128 v) { return (v > 0) - (v < 0); }

// (q - p) x (s - p), exact.
i128 cross(SnappedPoint p, SnappedPoint q, int64_t sx, int64_t sy) {
  return i128(int64_t(q.x) - p.x) * (sy - p.y) - i128(int64_t(q.y) - p.y) * (sx - p.x);
}

// Does triangle p, q, r keep samples lying exactly on its edge p-q?
bool keepsSamplesOnEdge(SnappedPoint p, SnappedPoint q, SnappedPoint r) {
  if (p.y == q.y) return r.y > p.y;  // horizontal: a top edge iff the interior is below (y down)
  // r.x minus the x of the edge line at height r.y is -cross(p, q, r) / (q.y - p.y).
  return sign(cross(p, q, r.x, r.y)) * sign(i128(q.y) - p.y) < 0;
}

int64_t sampleSubpixels(int p, FixedPointFormat f) {
  const int64_t s = f.subpixelsPerPixel();
  return int64_t(p) * s + s / 2;
}

int floorDiv(int64_t n, int64_t d) { return int(std::floor(double(n) / double(d))); }

struct Reference {
  Tri v;
  bool degenerate;
  std::array<bool, 3> keepsEdge;
  std::array<int, 3> rSide;

  explicit Reference(const Tri& t) : v(t) {
    degenerate = cross(v[0], v[1], v[2].x, v[2].y) == 0;
    for (int i = 0; i < 3; ++i) {
      const SnappedPoint p = v[i], q = v[(i + 1) % 3], r = v[(i + 2) % 3];
      keepsEdge[i] = !degenerate && keepsSamplesOnEdge(p, q, r);
      rSide[i] = sign(cross(p, q, r.x, r.y));
    }
  }

  // Does edge i (from v[i] to v[i+1]) let the sample through?
  bool edgePasses(int i, int64_t sx, int64_t sy) const {
    if (degenerate) return false;
    const int s = sign(cross(v[i], v[(i + 1) % 3], sx, sy));
    return s == 0 ? keepsEdge[i] : s == rSide[i];
  }

  // Per-edge masks over one tile (unclipped); the coverage is their AND.
  std::array<CoverageMask, 3> edgeMasks(int tx, int ty, FixedPointFormat f) const {
    std::array<CoverageMask, 3> m{};
    for (int ly = 0; ly < kTileSize; ++ly) {
      const int64_t sy = sampleSubpixels(ty * kTileSize + ly, f);
      for (int lx = 0; lx < kTileSize; ++lx) {
        const int64_t sx = sampleSubpixels(tx * kTileSize + lx, f);
        for (int i = 0; i < 3; ++i)
          if (edgePasses(i, sx, sy)) m[i] |= CoverageMask{1} << (ly * kTileSize + lx);
      }
    }
    return m;
  }
};

CoverageMask clipMaskOf(const PixelRect& r, int tx, int ty) {
  CoverageMask m = 0;
  for (int ly = 0; ly < kTileSize; ++ly)
    for (int lx = 0; lx < kTileSize; ++lx)
      if (r.contains(tx * kTileSize + lx, ty * kTileSize + ly))
        m |= CoverageMask{1} << (ly * kTileSize + lx);
  return m;
}

// Pixels whose centres lie in the closed box of the vertices, clipped: computed from the
// definition with real division, separately from the library's integer rounding.
PixelRect expectedBounds(const Tri& v, const PixelRect& clip, FixedPointFormat f) {
  const double s = f.subpixelsPerPixel();
  const double minX = std::min({v[0].x, v[1].x, v[2].x}), maxX = std::max({v[0].x, v[1].x, v[2].x});
  const double minY = std::min({v[0].y, v[1].y, v[2].y}), maxY = std::max({v[0].y, v[1].y, v[2].y});
  // Centre of pixel p is (p + 0.5) * s; first p with centre >= min, last with centre <= max.
  const PixelRect box{int(std::ceil(minX / s - 0.5)), int(std::ceil(minY / s - 0.5)),
                      int(std::floor(maxX / s - 0.5)) + 1, int(std::floor(maxY / s - 0.5)) + 1};
  return box.intersect(clip);
}

std::string describe(const Tri& t, const PixelRect& clip, FixedPointFormat f) {
  std::ostringstream o;
  o << "format " << f.name() << ", snapped vertices (" << t[0].x << ", " << t[0].y << ") ("
    << t[1].x << ", " << t[1].y << ") (" << t[2].x << ", " << t[2].y << "), clip {" << clip.x0
    << ", " << clip.y0 << ", " << clip.x1 << ", " << clip.y1 << "}";
  return o.str();
}

std::string hex(uint64_t m) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(m));
  return buf;
}

struct TileIndex {
  int x, y;
};

std::vector<TileIndex> tilesAround(const Tri& t, FixedPointFormat f);

// Checks one triangle on the given tiles; returns a description of the first disagreement, or an
// empty string.
std::string checkTriangle(const Tri& t, const PixelRect& clip, FixedPointFormat f,
                          const std::vector<TileIndex>& tiles) {
  const Reference ref(t);
  CoverageSetup setup;
  const SetupOutcome outcome = setupCoverage(t, clip, f, setup);
  const std::string what = describe(t, clip, f);

  if ((outcome == SetupOutcome::ZeroArea) != ref.degenerate)
    return what + ": ZeroArea must be reported exactly for collinear snapped vertices";
  if (ref.degenerate) return "";
  const PixelRect bounds = expectedBounds(t, clip, f);
  // A triangle narrower and shorter than two pixels is also dropped when none of the centres in
  // its bounds (at most 2x2) is covered, by the reference.
  const int64_t s = f.subpixelsPerPixel();
  const bool small = std::max({t[0].x, t[1].x, t[2].x}) - std::min({t[0].x, t[1].x, t[2].x}) < 2 * s &&
                     std::max({t[0].y, t[1].y, t[2].y}) - std::min({t[0].y, t[1].y, t[2].y}) < 2 * s;
  bool coversNone = small;
  if (small)
    for (const TileIndex& tile : tilesAround(t, f)) {
      const std::array<CoverageMask, 3> e = ref.edgeMasks(tile.x, tile.y, f);
      if ((e[0] & e[1] & e[2] & clipMaskOf(bounds, tile.x, tile.y)) != 0) coversNone = false;
    }
  if ((outcome == SetupOutcome::NoSamples) != (bounds.empty() || coversNone))
    return what + ": NoSamples must be reported exactly when no pixel centre is in the box, or "
                  "when a triangle under two pixels across covers none of those in its bounds";
  if (outcome == SetupOutcome::Accepted && setup.bounds != bounds) {
    std::ostringstream o;
    o << what << ": bounds {" << setup.bounds.x0 << ", " << setup.bounds.y0 << ", "
      << setup.bounds.x1 << ", " << setup.bounds.y1 << "}, expected {" << bounds.x0 << ", "
      << bounds.y0 << ", " << bounds.x1 << ", " << bounds.y1 << "}";
    return o.str();
  }

  for (const TileIndex& tile : tiles) {
    const std::array<CoverageMask, 3> edges = ref.edgeMasks(tile.x, tile.y, f);
    const CoverageMask unclipped = edges[0] & edges[1] & edges[2];
    const CoverageMask expected = unclipped & clipMaskOf(clip, tile.x, tile.y);
    std::ostringstream where;
    where << what << ", tile (" << tile.x << ", " << tile.y << ")";
    if (outcome != SetupOutcome::Accepted) {
      if (expected != 0) return where.str() + ": rejected triangle covers " + hex(expected);
      continue;
    }
    // Covered samples inside the clip must lie in the bounds, or the kernels would drop them.
    if ((expected & ~clipMaskOf(setup.bounds, tile.x, tile.y)) != 0)
      return where.str() + ": covered samples outside out.bounds: " + hex(expected);
    const CoverageMask got = coverageScalar(setup.edges, setup.bounds, tile.x, tile.y, f);
    if (got != expected)
      return where.str() + ": coverageScalar " + hex(got) + ", reference " + hex(expected);
    // classifyTile reads four corner samples; E is linear, so "negative at all four" means
    // negative at all 64 and "non-negative at all four" means non-negative at all 64. Both
    // classifications are therefore exact statements about the per-edge reference masks.
    const TileCoverage c = classifyTile(setup.edges, setup.bounds, tile.x, tile.y, f);
    const bool someEdgeRejectsAll = edges[0] == 0 || edges[1] == 0 || edges[2] == 0;
    const PixelRect tileRect{tile.x * kTileSize, tile.y * kTileSize, (tile.x + 1) * kTileSize,
                             (tile.y + 1) * kTileSize};
    const bool insideAll = unclipped == kFullMask && setup.bounds.intersect(tileRect) == tileRect;
    if (c == TileCoverage::Outside && expected != 0)
      return where.str() + ": classifyTile Outside but the reference covers " + hex(expected);
    if (c == TileCoverage::Inside && expected != kFullMask)
      return where.str() + ": classifyTile Inside but the reference covers " + hex(expected);
    if ((c == TileCoverage::Outside) != someEdgeRejectsAll)
      return where.str() + ": classifyTile Outside must hold iff one edge rejects all 64 samples";
    if ((c == TileCoverage::Inside) != insideAll)
      return where.str() + ": classifyTile Inside must hold iff all 64 samples pass, in bounds";
  }
  return "";
}

// Every tile meeting the vertices' pixel box grown by one tile, so tiles just outside the
// triangle are checked to stay empty.
std::vector<TileIndex> tilesAround(const Tri& t, FixedPointFormat f) {
  const int64_t s = f.subpixelsPerPixel();
  const int x0 = floorDiv(floorDiv(std::min({t[0].x, t[1].x, t[2].x}), s), kTileSize) - 1;
  const int x1 = floorDiv(floorDiv(std::max({t[0].x, t[1].x, t[2].x}), s), kTileSize) + 1;
  const int y0 = floorDiv(floorDiv(std::min({t[0].y, t[1].y, t[2].y}), s), kTileSize) - 1;
  const int y1 = floorDiv(floorDiv(std::max({t[0].y, t[1].y, t[2].y}), s), kTileSize) + 1;
  std::vector<TileIndex> tiles;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) tiles.push_back({x, y});
  return tiles;
}

int64_t uniform(std::mt19937_64& rng, int64_t lo, int64_t hi) {
  return std::uniform_int_distribution<int64_t>(lo, hi)(rng);
}

SnappedPoint point(int64_t x, int64_t y) { return {int32_t(x), int32_t(y)}; }

// A window of the plane where small random triangles are placed and the clip rectangle that cuts
// them (not tile-aligned, so rectMask and bounds clipping matter).
constexpr int kAreaPixels = 40;
const PixelRect kAreaClip{3, 2, 37, 35};

// Runs `count` triangles from `make` through checkTriangle, stopping at the first failure.
template <class Make>
void runRandom(uint64_t seed, int count, const PixelRect& clip, Make make) {
  for (const FixedPointFormat f : kFormats) {
    const uint64_t formatSeed = seed ^ uint64_t(f.fractionBits);
    SCOPED_TRACE(testing::Message()
                 << "std::mt19937_64 seed " << formatSeed << ", format " << f.name());
    std::mt19937_64 rng(formatSeed);
    for (int i = 0; i < count; ++i) {
      const Tri t = make(rng, f);
      const std::string error = checkTriangle(t, clip, f, tilesAround(t, f));
      if (!error.empty()) FAIL() << "triangle " << i << ": " << error;
    }
  }
}

// ---- Random triangles against the reference --------------------------------------------------

TEST(Coverage, ScalarMatchesReferenceOnRandomTriangles) {
  // Arbitrary subpixel positions at every scale from one pixel to the whole area.
  runRandom(0xC0FE0001, 6000, kAreaClip, [](std::mt19937_64& rng, FixedPointFormat f) {
    const int64_t s = f.subpixelsPerPixel();
    const int64_t size =
        int64_t(std::exp2(std::uniform_real_distribution<double>(0, 5.6)(rng)) * s);
    const int64_t cx = uniform(rng, -4 * s, (kAreaPixels + 4) * s),
                  cy = uniform(rng, -4 * s, (kAreaPixels + 4) * s);
    Tri t;
    for (auto& p : t) p = point(cx + uniform(rng, -size, size), cy + uniform(rng, -size, size));
    return t;
  });
}

TEST(Coverage, ScalarMatchesReferenceWithVerticesOnPixelCentres) {
  // Vertices on pixel centres (and on the half-pixel grid between them): every edge then passes
  // exactly through samples, and many vertices are samples, so the fill rule decides a large
  // share of the samples.
  runRandom(0xC0FE0002, 6000, kAreaClip, [](std::mt19937_64& rng, FixedPointFormat f) {
    const int64_t s = f.subpixelsPerPixel();
    const bool halfGrid = uniform(rng, 0, 3) == 0;
    const int64_t step = halfGrid ? s / 2 : s;
    const int64_t size = uniform(rng, 1, 16);
    const int64_t cx = uniform(rng, -2, kAreaPixels + 2), cy = uniform(rng, -2, kAreaPixels + 2);
    Tri t;
    for (auto& p : t)
      p = point((cx + uniform(rng, -size, size)) * s + s / 2 +
                    (halfGrid ? uniform(rng, -size, size) * step : 0),
                (cy + uniform(rng, -size, size)) * s + s / 2 +
                    (halfGrid ? uniform(rng, -size, size) * step : 0));
    return t;
  });
}

TEST(Coverage, ScalarMatchesReferenceOnTinyTriangles) {
  // Triangles a few subpixels across around a pixel centre or a pixel corner: they cover zero or
  // one sample, often through a vertex or an edge on the sample, and many are degenerate.
  runRandom(0xC0FE0003, 5000, kAreaClip, [](std::mt19937_64& rng, FixedPointFormat f) {
    const int64_t s = f.subpixelsPerPixel();
    const int64_t cx = uniform(rng, 0, kAreaPixels) * s + (uniform(rng, 0, 1) ? s / 2 : 0);
    const int64_t cy = uniform(rng, 0, kAreaPixels) * s + (uniform(rng, 0, 1) ? s / 2 : 0);
    const int64_t r = uniform(rng, 1, 4);
    Tri t;
    for (auto& p : t) p = point(cx + uniform(rng, -r, r), cy + uniform(rng, -r, r));
    return t;
  });
}

TEST(Coverage, SmallTrianglesCoveringNoCentreAreDropped) {
  // Triangles up to two and a half pixels across at random subpixel positions: setup tests the
  // centres of those under two pixels across and drops the ones that cover none (checkTriangle
  // holds it to exactly that, and to never dropping a triangle that covers a sample). Both kinds
  // must occur in numbers, or the test would show nothing.
  int droppedWithCentresInBounds = 0, smallDrawn = 0;
  runRandom(0xC0FE0009, 6000, kAreaClip, [&](std::mt19937_64& rng, FixedPointFormat f) {
    const int64_t s = f.subpixelsPerPixel();
    const int64_t size = uniform(rng, 1, 5 * s / 4);
    const int64_t cx = uniform(rng, 0, kAreaPixels * s), cy = uniform(rng, 0, kAreaPixels * s);
    Tri t;
    for (auto& p : t) p = point(cx + uniform(rng, -size, size), cy + uniform(rng, -size, size));
    CoverageSetup setup;
    const SetupOutcome outcome = setupCoverage(t, kAreaClip, f, setup);
    if (outcome == SetupOutcome::NoSamples && !expectedBounds(t, kAreaClip, f).empty())
      ++droppedWithCentresInBounds;
    if (outcome == SetupOutcome::Accepted && setup.bounds.x1 - setup.bounds.x0 <= 2 &&
        setup.bounds.y1 - setup.bounds.y0 <= 2)
      ++smallDrawn;
    return t;
  });
  EXPECT_GT(droppedWithCentresInBounds, 1000);
  EXPECT_GT(smallDrawn, 1000);
}

TEST(Coverage, ScalarMatchesReferenceOnSlivers) {
  // Long edges with the third vertex on the edge line (degenerate) or one subpixel off it: the
  // area is tiny, the samples near the line are decided by a difference of +-1 in E.
  runRandom(0xC0FE0004, 4000, kAreaClip, [](std::mt19937_64& rng, FixedPointFormat f) {
    const int64_t s = f.subpixelsPerPixel();
    const bool centred = uniform(rng, 0, 1) == 1;
    const auto randomPoint = [&] {
      if (centred)
        return point(uniform(rng, -2, kAreaPixels + 2) * s + s / 2,
                     uniform(rng, -2, kAreaPixels + 2) * s + s / 2);
      return point(uniform(rng, -2 * s, (kAreaPixels + 2) * s),
                   uniform(rng, -2 * s, (kAreaPixels + 2) * s));
    };
    const SnappedPoint p = randomPoint(), q = randomPoint();
    const int64_t dx = int64_t(q.x) - p.x, dy = int64_t(q.y) - p.y;
    const int64_t g = std::max<int64_t>(1, std::gcd(std::abs(dx), std::abs(dy)));
    // A lattice point of the line p-q (k of the g steps along it), nudged by at most a subpixel.
    const int64_t k = uniform(rng, -g / 2, g + g / 2);
    const SnappedPoint r =
        point(p.x + k * (dx / g) + uniform(rng, -1, 1), p.y + k * (dy / g) + uniform(rng, -1, 1));
    return Tri{p, q, r};
  });
}

TEST(Coverage, ScalarMatchesReferenceOnCollinearVertices) {
  // Snapped vertices exactly on one line (including repeated vertices) have zero area; nothing
  // may be drawn and setup must say ZeroArea.
  runRandom(0xC0FE0005, 1000, kAreaClip, [](std::mt19937_64& rng, FixedPointFormat f) {
    const int64_t s = f.subpixelsPerPixel();
    const SnappedPoint p =
        point(uniform(rng, 0, kAreaPixels * s), uniform(rng, 0, kAreaPixels * s));
    const int64_t dx = uniform(rng, -3 * s, 3 * s), dy = uniform(rng, -3 * s, 3 * s);
    const int64_t m = uniform(rng, -4, 4), n = uniform(rng, -4, 4);
    return Tri{p, point(p.x + m * dx, p.y + m * dy), point(p.x + n * dx, p.y + n * dy)};
  });
}

// Triangles near a corner of the guard band (coordinates up to its limit), checked on every tile
// around them, with a clip rectangle at that corner.
void runNearGuardBand(uint64_t seed, int count, int cornerX, int cornerY, bool onCentres) {
  for (const FixedPointFormat f : kFormats) {
    const uint64_t formatSeed = seed ^ uint64_t(f.fractionBits);
    SCOPED_TRACE(testing::Message()
                 << "std::mt19937_64 seed " << formatSeed << ", format " << f.name() << ", corner ("
                 << cornerX << ", " << cornerY << ")");
    std::mt19937_64 rng(formatSeed);
    const int64_t s = f.subpixelsPerPixel(), g = f.guardBandSubpixels();
    const int gp = int(f.guardBandPixels());
    // The last 32 pixels of the band in each direction; the viewport lies inside the band.
    const PixelRect clip{cornerX > 0 ? gp - 32 : -gp, cornerY > 0 ? gp - 32 : -gp,
                         cornerX > 0 ? gp : -gp + 32, cornerY > 0 ? gp : -gp + 32};
    for (int i = 0; i < count; ++i) {
      Tri t;
      for (auto& p : t) {
        int64_t dx = uniform(rng, 0, 30 * s), dy = uniform(rng, 0, 30 * s);
        if (onCentres) dx = dx / s * s + s / 2, dy = dy / s * s + s / 2;
        // Occasionally exactly on the limit, where snapping clamps.
        if (uniform(rng, 0, 7) == 0) dx = 0;
        if (uniform(rng, 0, 7) == 0) dy = 0;
        p = point(cornerX > 0 ? g - dx : -g + dx, cornerY > 0 ? g - dy : -g + dy);
      }
      const std::string error = checkTriangle(t, clip, f, tilesAround(t, f));
      if (!error.empty()) FAIL() << "triangle " << i << ": " << error;
    }
  }
}

TEST(Coverage, ScalarMatchesReferenceNearTheGuardBandLimit) {
  int corner = 0;
  for (const int cx : {-1, 1})
    for (const int cy : {-1, 1}) {
      runNearGuardBand(0xC0FE0010 + corner, 300, cx, cy, false);
      runNearGuardBand(0xC0FE0020 + corner, 200, cx, cy, true);
      ++corner;
    }
}

TEST(Coverage, ScalarMatchesReferenceOnTrianglesSpanningTheGuardBand) {
  // Vertices anywhere in the guard band, edge functions near their largest magnitude. The
  // triangles span millions of tiles, so the tiles checked are those at and around the
  // vertices, where the edges meet, plus random ones inside the box.
  for (const FixedPointFormat f : kFormats) {
    const uint64_t seed = 0xC0FE0030 ^ uint64_t(f.fractionBits);
    SCOPED_TRACE(testing::Message() << "std::mt19937_64 seed " << seed << ", format " << f.name());
    std::mt19937_64 rng(seed);
    const int64_t g = f.guardBandSubpixels(), s = f.subpixelsPerPixel();
    const int gp = int(f.guardBandPixels());
    const PixelRect clip{-gp, -gp, gp, gp};
    for (int i = 0; i < 600; ++i) {
      Tri t;
      for (auto& p : t) {
        const auto coord = [&] {
          switch (uniform(rng, 0, 3)) {
            case 0:
              return uniform(rng, 0, 1) ? g : -g;  // on the limit
            case 1:
              return (uniform(rng, -gp, gp - 1) * s + s / 2);  // a pixel centre
            default:
              return uniform(rng, -g, g);
          }
        };
        p = point(coord(), coord());
      }
      std::vector<TileIndex> tiles;
      for (const SnappedPoint& p : t) {
        const int tx = floorDiv(floorDiv(std::clamp<int64_t>(p.x, -g, g - 1), s), kTileSize);
        const int ty = floorDiv(floorDiv(std::clamp<int64_t>(p.y, -g, g - 1), s), kTileSize);
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) tiles.push_back({tx + dx, ty + dy});
      }
      const int lo = -gp / kTileSize, hi = gp / kTileSize - 1;
      for (int k = 0; k < 24; ++k)
        tiles.push_back({int(uniform(rng, lo, hi)), int(uniform(rng, lo, hi))});
      // Tiles along the edges, where the partial tiles are.
      for (int e = 0; e < 3; ++e) {
        const SnappedPoint a = t[e], b = t[(e + 1) % 3];
        for (int k = 0; k <= 8; ++k) {
          const int64_t x = a.x + (int64_t(b.x) - a.x) * k / 8,
                        y = a.y + (int64_t(b.y) - a.y) * k / 8;
          tiles.push_back({floorDiv(floorDiv(std::clamp<int64_t>(x, -g, g - 1), s), kTileSize),
                           floorDiv(floorDiv(std::clamp<int64_t>(y, -g, g - 1), s), kTileSize)});
        }
      }
      const std::string error = checkTriangle(t, clip, f, tiles);
      if (!error.empty()) FAIL() << "triangle " << i << ": " << error;
    }
  }
}

// ---- Watertightness on random meshes ------------------------------------------------------------

TEST(Coverage, RandomMeshCoversEverySampleOnce) {
  // A jittered grid of vertices, each quad split along a random diagonal: the triangles tile the
  // plane around the clip rectangle without overlap, so the fill rule must give every sample of
  // the clip rectangle to exactly one triangle. Half the vertices sit on pixel centres, so
  // shared edges and shared vertices through samples are common.
  for (const FixedPointFormat f : kFormats) {
    const uint64_t seed = 0xC0FE0040 ^ uint64_t(f.fractionBits);
    SCOPED_TRACE(testing::Message() << "std::mt19937_64 seed " << seed << ", format " << f.name());
    std::mt19937_64 rng(seed);
    const int64_t s = f.subpixelsPerPixel();
    constexpr int kCells = 12, kSpacing = 4;  // pixels; the grid spans [-8, 40]
    const PixelRect clip{0, 0, 32, 32};
    for (int mesh = 0; mesh < 40; ++mesh) {
      std::vector<SnappedPoint> grid((kCells + 1) * (kCells + 1));
      for (int j = 0; j <= kCells; ++j)
        for (int i = 0; i <= kCells; ++i) {
          const int64_t x = (int64_t(i) * kSpacing - 8) * s, y = (int64_t(j) * kSpacing - 8) * s;
          // Jitter below 3/4 pixel keeps every triangle's orientation (no fold-over).
          const int64_t j3 = 3 * s / 4 - 1;
          grid[j * (kCells + 1) + i] =
              uniform(rng, 0, 1)
                  ? point(x + uniform(rng, -1, 0) * s + s / 2, y + uniform(rng, -1, 0) * s + s / 2)
                  : point(x + uniform(rng, -j3, j3), y + uniform(rng, -j3, j3));
        }
      std::array<int, 32 * 32> count{};
      for (int j = 0; j < kCells; ++j)
        for (int i = 0; i < kCells; ++i) {
          const SnappedPoint a = grid[j * (kCells + 1) + i], b = grid[j * (kCells + 1) + i + 1];
          const SnappedPoint c = grid[(j + 1) * (kCells + 1) + i],
                             d = grid[(j + 1) * (kCells + 1) + i + 1];
          const std::array<Tri, 2> tris = uniform(rng, 0, 1)
                                              ? std::array<Tri, 2>{Tri{a, b, d}, Tri{a, d, c}}
                                              : std::array<Tri, 2>{Tri{a, b, c}, Tri{b, d, c}};
          for (const Tri& t : tris) {
            CoverageSetup setup;
            if (setupCoverage(t, clip, f, setup) != SetupOutcome::Accepted) continue;
            for (int ty = setup.bounds.y0 / 8; ty <= (setup.bounds.y1 - 1) / 8; ++ty)
              for (int tx = setup.bounds.x0 / 8; tx <= (setup.bounds.x1 - 1) / 8; ++tx) {
                const CoverageMask m = coverageScalar(setup.edges, setup.bounds, tx, ty, f);
                for (int bit = 0; bit < 64; ++bit)
                  if ((m >> bit) & 1) ++count[(ty * 8 + bit / 8) * 32 + tx * 8 + bit % 8];
              }
          }
        }
      for (int p = 0; p < 32 * 32; ++p)
        if (count[p] != 1)
          FAIL() << "mesh " << mesh << ": pixel (" << p % 32 << ", " << p / 32 << ") covered "
                 << count[p] << " times";
    }
  }
}

TEST(Coverage, RandomSharedEdgesCoverTheirSamplesOnce) {
  // Two triangles on opposite sides of a random edge through pixel centres: each sample on the
  // open edge is strictly inside the other two edges of both, so the shared edge alone decides,
  // and it is top-left for exactly one of them.
  for (const FixedPointFormat f : kFormats) {
    const uint64_t seed = 0xC0FE0050 ^ uint64_t(f.fractionBits);
    SCOPED_TRACE(testing::Message() << "std::mt19937_64 seed " << seed << ", format " << f.name());
    std::mt19937_64 rng(seed);
    const int64_t s = f.subpixelsPerPixel();
    const PixelRect clip{-64, -64, 64, 64};
    int samplesOnEdges = 0;
    for (int i = 0; i < 3000; ++i) {
      const auto centre = [&] {
        return point(uniform(rng, 0, 15) * s + s / 2, uniform(rng, 0, 15) * s + s / 2);
      };
      const SnappedPoint p = centre(), q = centre();
      if (p == q) continue;
      SnappedPoint r1 = point(uniform(rng, -8 * s, 24 * s), uniform(rng, -8 * s, 24 * s));
      SnappedPoint r2 = point(uniform(rng, -8 * s, 24 * s), uniform(rng, -8 * s, 24 * s));
      const int side1 = sign(cross(p, q, r1.x, r1.y)), side2 = sign(cross(p, q, r2.x, r2.y));
      if (side1 == 0 || side2 == 0) continue;
      if (side1 == side2) r2 = point(2 * int64_t(p.x) - r2.x, 2 * int64_t(p.y) - r2.y);  // reflect
      if (sign(cross(p, q, r2.x, r2.y)) != -side1) continue;
      const Tri ta = uniform(rng, 0, 1) ? Tri{p, q, r1} : Tri{q, p, r1};
      const Tri tb = uniform(rng, 0, 1) ? Tri{p, q, r2} : Tri{r2, q, p};
      CoverageSetup sa, sb;
      // A triangle under two pixels across that covers none of its centres is dropped at setup
      // (NoSamples): it covers nothing here, and the other must cover the edge's samples.
      const SetupOutcome oa = setupCoverage(ta, clip, f, sa), ob = setupCoverage(tb, clip, f, sb);
      ASSERT_NE(oa, SetupOutcome::ZeroArea);
      ASSERT_NE(ob, SetupOutcome::ZeroArea);
      for (int ty = 0; ty < 2; ++ty)
        for (int tx = 0; tx < 2; ++tx) {
          const CoverageMask a = oa == SetupOutcome::Accepted
                                     ? coverageScalar(sa.edges, sa.bounds, tx, ty, f) : 0;
          const CoverageMask b = ob == SetupOutcome::Accepted
                                     ? coverageScalar(sb.edges, sb.bounds, tx, ty, f) : 0;
          ASSERT_EQ(a & b, 0u) << describe(ta, clip, f) << " and " << describe(tb, clip, f);
          for (int bit = 0; bit < 64; ++bit) {
            const int64_t sx = sampleSubpixels(tx * 8 + bit % 8, f),
                          sy = sampleSubpixels(ty * 8 + bit / 8, f);
            const bool onOpenEdge = cross(p, q, sx, sy) == 0 && std::min(p.x, q.x) <= sx &&
                                    sx <= std::max(p.x, q.x) && std::min(p.y, q.y) <= sy &&
                                    sy <= std::max(p.y, q.y) && !(sx == p.x && sy == p.y) &&
                                    !(sx == q.x && sy == q.y);
            if (!onOpenEdge) continue;
            ++samplesOnEdges;
            ASSERT_EQ(((a | b) >> bit) & 1, 1u)
                << "sample (" << tx * 8 + bit % 8 << ", " << ty * 8 + bit / 8
                << ") on the shared edge is covered by neither: " << describe(ta, clip, f)
                << " and " << describe(tb, clip, f);
          }
        }
    }
    // The edges run between pixel centres of a 16x16 block, so most of them pass through samples.
    EXPECT_GT(samplesOnEdges, 3000);
  }
}

// ---- rectMask -----------------------------------------------------------------------------------

TEST(Coverage, RectMaskExactCases) {
  EXPECT_EQ(rectMask({0, 0, 8, 8}, 0, 0), kFullMask);
  EXPECT_EQ(rectMask({-100, -100, 100, 100}, -2, 3), kFullMask);
  EXPECT_EQ(rectMask({0, 0, 0, 8}, 0, 0), 0u);  // empty in x
  EXPECT_EQ(rectMask({0, 5, 8, 5}, 0, 0), 0u);  // empty in y
  EXPECT_EQ(rectMask({5, 5, 2, 7}, 0, 0), 0u);  // inverted
  EXPECT_EQ(rectMask({0, 0, 8, 8}, 1, 0), 0u);  // the neighbouring tile
  EXPECT_EQ(rectMask({0, 0, 8, 8}, 0, -1), 0u);
  // Pixels (1, 2), (2, 2), (1, 3), (2, 3): bits 17, 18, 25, 26.
  EXPECT_EQ(rectMask({1, 2, 3, 4}, 0, 0),
            (1ull << 17) | (1ull << 18) | (1ull << 25) | (1ull << 26));
  // A single pixel in the last bit.
  EXPECT_EQ(rectMask({7, 7, 8, 8}, 0, 0), 1ull << 63);
  EXPECT_EQ(rectMask({15, 15, 16, 16}, 1, 1), 1ull << 63);
  // Row 0 only, and column 0 only.
  EXPECT_EQ(rectMask({-5, 0, 50, 1}, 0, 0), 0xFFull);
  EXPECT_EQ(rectMask({0, -5, 1, 50}, 0, 0), 0x0101010101010101ull);
  // Column 7 only.
  EXPECT_EQ(rectMask({7, 0, 8, 8}, 0, 0), 0x8080808080808080ull);
  // Negative tile: pixels x in [-3, 2) meet tile -1 in its local columns 5..7, row 0.
  EXPECT_EQ(rectMask({-3, -8, 2, -7}, -1, -1), 0xE0ull);
  // The same rectangle seen from tile (0, -1): local columns 0..1, row 0.
  EXPECT_EQ(rectMask({-3, -8, 2, -7}, 0, -1), 0x03ull);
  // Rows 6..7 of tile (2, 1), all columns: the rectangle starts mid-tile in y.
  EXPECT_EQ(rectMask({0, 14, 100, 100}, 2, 1), 0xFFFF000000000000ull);
  // Far from the origin (near the 24.4 guard band).
  const int far = 1 << 22;
  EXPECT_EQ(rectMask({far - 8, far - 8, far, far}, far / 8 - 1, far / 8 - 1), kFullMask);
  EXPECT_EQ(rectMask({-far, -far, -far + 1, -far + 2}, -far / 8, -far / 8), 0x0101ull);
}

TEST(Coverage, RectMaskMatchesContainsEverywhere) {
  // Every rectangle with corners in [-9, 17] against tiles -1..1: the mask is the set of pixels
  // the rectangle contains, bit (x % 8, y % 8).
  for (int x0 = -9; x0 <= 17; x0 += 2)
    for (int x1 = x0 - 1; x1 <= 17; x1 += 3)
      for (int y0 = -9; y0 <= 17; y0 += 3)
        for (int y1 = y0 - 1; y1 <= 17; y1 += 2) {
          const PixelRect r{x0, y0, x1, y1};
          for (int ty = -1; ty <= 1; ++ty)
            for (int tx = -1; tx <= 1; ++tx)
              ASSERT_EQ(rectMask(r, tx, ty), clipMaskOf(r, tx, ty))
                  << "rect {" << x0 << ", " << y0 << ", " << x1 << ", " << y1 << "}, tile (" << tx
                  << ", " << ty << ")";
        }
}

// ---- classifyTile on hand-built cases -------------------------------------------------------

TEST(Coverage, ClassifyTileExactCases) {
  const FixedPointFormat f = FixedPointFormat::d24_4();
  const int64_t s = f.subpixelsPerPixel();
  // A right triangle with legs of 40 pixels from the origin: x >= 0, y >= 0, x + y <= 40.
  const Tri t{point(0, 0), point(40 * s, 0), point(0, 40 * s)};
  CoverageSetup setup;
  ASSERT_EQ(setupCoverage(t, {0, 0, 64, 64}, f, setup), SetupOutcome::Accepted);
  // Tile (0, 0): all samples have x + y <= 15 < 40.
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, 0, 0, f), TileCoverage::Inside);
  // Tile (3, 0): samples x + y from 25 to 39, still all inside.
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, 3, 0, f), TileCoverage::Inside);
  // Tile (4, 0): sample (32.5, 0.5) is inside, (39.5, 7.5) is not.
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, 4, 0, f), TileCoverage::Partial);
  // Tile (5, 0): every sample has x >= 40.5: the hypotenuse rejects all.
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, 5, 0, f), TileCoverage::Outside);
  // Tiles left of and above the triangle.
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, -1, 0, f), TileCoverage::Outside);
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, 0, -1, f), TileCoverage::Outside);
  // Tile (2, 2): samples x + y from 33 to 47 straddle the hypotenuse.
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, 2, 2, f), TileCoverage::Partial);
  // Tile (3, 3): x + y >= 49 everywhere: the hypotenuse alone rejects the tile.
  EXPECT_EQ(classifyTile(setup.edges, setup.bounds, 3, 3, f), TileCoverage::Outside);

  // With the clip cutting the tile, all-inside edges are not enough for Inside.
  CoverageSetup clipped;
  ASSERT_EQ(setupCoverage(t, {0, 0, 6, 64}, f, clipped), SetupOutcome::Accepted);
  EXPECT_EQ(classifyTile(clipped.edges, clipped.bounds, 0, 0, f), TileCoverage::Partial);
  EXPECT_EQ(coverageScalar(clipped.edges, clipped.bounds, 0, 0, f), 0x3F3F3F3F3F3F3F3Full);

  // A thin wedge pointing at tile (0, 0) from the right, its tip at x = 7.875, right of every
  // sample (x <= 7.5): each edge alone keeps some samples of the tile, so the per-edge corner test
  // cannot reject it, and the tile is Partial with an empty mask.
  const Tri wedge{point(126, 4 * s), point(30 * s, -20 * s), point(30 * s, 28 * s)};
  CoverageSetup w;
  ASSERT_EQ(setupCoverage(wedge, {-64, -64, 64, 64}, f, w), SetupOutcome::Accepted);
  EXPECT_EQ(classifyTile(w.edges, w.bounds, 0, 0, f), TileCoverage::Partial);
  EXPECT_EQ(coverageScalar(w.edges, w.bounds, 0, 0, f), 0u);
}

}  // namespace
}  // namespace rast
