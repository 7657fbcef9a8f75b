#include "reference/interpolation_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pipeline/draw.h"
#include "reference/exact_rasterizer.h"

namespace rast::reference {
namespace {

constexpr double kFloatUnit = 0x1p-24;

struct PassThroughVS {
  using Vertex = ShadedVertex<2>;
  static constexpr int kVaryings = 2;
  ShadedVertex<2> operator()(const Vertex& v) const { return v; }
};

// Records the varyings and depth handed to the pixel shader (one triangle per draw).
struct CaptureShader {
  static constexpr int kVaryings = 2;
  static constexpr bool kMayDiscard = false;
  std::vector<Varyings<2>>* varyings;
  std::vector<float>* depth;
  int width;
  PixelResult operator()(const Fragment<2>& f) const {
    (*varyings)[size_t(f.y) * width + f.x] = f.varyings;
    (*depth)[size_t(f.y) * width + f.x] = f.depth;
    return {};
  }
};

double floatUlp(double x) {
  x = std::abs(x);
  if (x < std::numeric_limits<float>::min()) return 0x1p-149;
  return std::ldexp(1.0, std::ilogb(x) - 23);
}

// Plane value at the anchor and gradient (per pixel) through three window points, in double.
struct Plane {
  double at, ddx, ddy;
  double termScale(double dx, double dy) const {
    return std::abs(at) + std::abs(ddx * dx) + std::abs(ddy * dy);
  }
};
Plane planeThrough(const std::array<double, 3>& x, const std::array<double, 3>& y,
                   const std::array<double, 3>& value, double ax, double ay) {
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const double d1 = value[1] - value[0], d2 = value[2] - value[0];
  const double ddx = (d1 * (y[2] - y[0]) - d2 * (y[1] - y[0])) / area;
  const double ddy = (d2 * (x[1] - x[0]) - d1 * (x[2] - x[0])) / area;
  return {value[0] + ddx * (ax - x[0]) + ddy * (ay - y[0]), ddx, ddy};
}

void raise(ErrorMaximum& m, double error, double scale, double exact) {
  m.scaleUlps = std::max(m.scaleUlps, error / (kFloatUnit * scale));
  m.valueUlps = std::max(m.valueUlps, error / floatUlp(exact));
  ++m.pixels;
}

}  // namespace

void ErrorMaximum::add(const ErrorMaximum& o) {
  scaleUlps = std::max(scaleUlps, o.scaleUlps);
  valueUlps = std::max(valueUlps, o.valueUlps);
  pixels += o.pixels;
}

void InterpolationErrors::add(const InterpolationErrors& o) {
  depth.add(o.depth);
  for (int j = 0; j < 2; ++j) varyings[j].add(o.varyings[j]);
  affineScaleUlps = std::max(affineScaleUlps, o.affineScaleUlps);
}

Status measureInterpolation(const std::array<ShadedVertex<2>, 3>& triangle, PipelineState state,
                            int width, int height, InterpolationErrors& out) {
  state.viewport = {0, 0, width, height};
  state.positionSpace = PositionSpace::Clip;
  state.depth.compare = CompareOp::Always;
  state.depth.write = false;
  const bool floatMode = state.rasterMode == RasterMode::Float;
  const ScreenMapping mapping = ScreenMapping::forState(state);
  WindowTriangle window;
  std::array<double, 3> depth, invW;
  std::array<std::array<double, 3>, 2> value;
  for (int k = 0; k < 3; ++k) {
    const WindowPosition p = mapping.toWindow(glm::dvec4(triangle[k].position));
    window[k] = {p.x, p.y};
    depth[k] = p.z;
    invW[k] = p.invW;
    for (int j = 0; j < 2; ++j) value[j][k] = triangle[k].varyings[j];
  }
  // Float mode rasterizes and interpolates over the float vertices.
  if (floatMode) window = roundedToFloat(window);
  GridTriangle grid;
  if (!toGrid(window, {!floatMode, state.format, SampleRule::TopLeft}, grid))
    return Status::error("the triangle's exact geometry cannot be represented on an integer grid");
  std::array<double, 3> sx, sy;
  for (int k = 0; k < 3; ++k) {
    sx[k] = std::ldexp(double(grid.x[k]), -grid.fractionBits);
    sy[k] = std::ldexp(double(grid.y[k]), -grid.fractionBits);
  }

  std::vector<Varyings<2>> varyings(size_t(width) * height);
  std::vector<float> fragmentDepth(size_t(width) * height, NAN);
  const std::vector<ShadedVertex<2>> vertices(triangle.begin(), triangle.end());
  const std::vector<uint32_t> indices = {0, 1, 2};
  Framebuffer fb(width, height, true);
  PipelineStatistics stats;
  const PassThroughVS vs;
  const CaptureShader ps{&varyings, &fragmentDepth, width};
  if (Status s = draw(fb, state, DrawCall<PassThroughVS, CaptureShader>{vertices, indices, vs, ps}, stats); !s)
    return s;
  if (stats.clipClipped != 0) {
    out.clipped = true;
    return Status::ok();
  }
  if (stats.samplesCovered == 0) return Status::ok();
  // The anchor of the pipeline's planes: the corner of the triangle's bounds, the bounding box of
  // the pixel centres inside its vertices' bounding box, clipped to the viewport.
  const double minX = std::min({sx[0], sx[1], sx[2]}), minY = std::min({sy[0], sy[1], sy[2]});
  const int ax = std::max(0, int(std::ceil(minX - 0.5)));
  const int ay = std::max(0, int(std::ceil(minY - 0.5)));

  const Plane zPlane = planeThrough(sx, sy, depth, ax + 0.5, ay + 0.5);
  const Plane rPlane = planeThrough(sx, sy, invW, ax + 0.5, ay + 0.5);
  std::array<Plane, 2> qPlane;
  for (int j = 0; j < 2; ++j) {
    std::array<double, 3> q;
    for (int k = 0; k < 3; ++k) q[k] = value[j][k] * invW[k];
    qPlane[j] = planeThrough(sx, sy, q, ax + 0.5, ay + 0.5);
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      if (fb.countPlane()[i] == 0) continue;
      const std::array<double, 3> l = barycentricAtPixelCentre(grid, x, y);
      const double dx = x - ax, dy = y - ay;
      // The pipeline clamps depth to [0, 1], which only moves it towards the exact value.
      const double z = std::clamp(interpolateLinear(l, depth), 0.0, 1.0);
      raise(out.depth, std::abs(double(fragmentDepth[i]) - z), zPlane.termScale(dx, dy), z);
      const double r = interpolateLinear(l, invW);
      for (int j = 0; j < 2; ++j) {
        const double exact = interpolatePerspective(l, invW, value[j]);
        const double scale =
            (qPlane[j].termScale(dx, dy) + std::abs(exact) * rPlane.termScale(dx, dy)) / r +
            std::abs(exact);
        raise(out.varyings[j], std::abs(double(varyings[i][j]) - exact), scale, exact);
        if (j == 0) {
          const double affine = float(interpolateLinear(l, value[0]));
          out.affineScaleUlps =
              std::max(out.affineScaleUlps, std::abs(affine - exact) / (kFloatUnit * scale));
        }
      }
    }
  return Status::ok();
}

}  // namespace rast::reference
