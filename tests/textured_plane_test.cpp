// A textured ground plane in perspective (shaders_cpp/textured.h): mip selection from the
// screen-space derivatives of the texture coordinates.
//
// The texture is a "level ramp": level k is the constant red k/8, so the red a trilinear sample
// returns is its level of detail / 8, and the picture shows which level each pixel chose. The
// expected level of detail comes from the plane in closed form: the ray through a window point
// meets y = 0 at a point whose (x, z) / kPeriod are the texture coordinates, so the coordinates
// and their derivatives along window x and y are known in double at every pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

#include "pipeline/draw.h"
#include "scene/camera.h"
#include "shaders_cpp/textured.h"

namespace rast {
namespace {

constexpr int kWidth = 128, kHeight = 96;
constexpr double kPeriod = 4.0;   // world units per texture repeat
constexpr int kTextureSize = 64;  // 7 levels, 0..6
constexpr float kHalfX = 100.0f, kNearZ = 10.0f, kFarZ = -150.0f;

Texture levelRampTexture() {
  std::vector<TextureLevel> levels;
  for (int k = 0; k < mipLevelCount(kTextureSize, kTextureSize); ++k) {
    const int n = mipLevelExtent(kTextureSize, k);
    levels.push_back({n, n, std::vector<glm::vec4>(size_t(n) * n, glm::vec4(k / 8.0f, 0, 0, 1))});
  }
  Texture t;
  EXPECT_TRUE(Texture::fromLevels(std::move(levels), t));
  return t;
}

Camera planeCamera() {
  Camera c;
  c.eye = {0, 2, 4};
  c.target = {0, 0, -10};
  c.fovYDegrees = 60.0f;
  c.nearPlane = 0.5f;
  c.farPlane = 400.0f;
  return c;
}

// The texture coordinates where the ray through window point (wx, wy) meets the plane; false
// where it misses it (above the horizon or beyond its far edge).
struct PlaneView {
  glm::dmat4 inverse = glm::inverse(glm::dmat4(planeCamera().viewProjection(float(kWidth) / kHeight)));

  bool uvAt(double wx, double wy, glm::dvec2& uv) const {
    const double nx = wx / (0.5 * kWidth) - 1.0, ny = 1.0 - wy / (0.5 * kHeight);
    const glm::dvec4 a = inverse * glm::dvec4(nx, ny, -1.0, 1.0);
    const glm::dvec4 b = inverse * glm::dvec4(nx, ny, 1.0, 1.0);
    const glm::dvec3 p = glm::dvec3(a) / a.w, q = glm::dvec3(b) / b.w;
    if (!(p.y > 0 && q.y < 0)) return false;
    const glm::dvec3 hit = p + (q - p) * (p.y / (p.y - q.y));
    if (hit.z < kFarZ || hit.z > kNearZ || std::abs(hit.x) > kHalfX) return false;
    uv = glm::dvec2(hit.x, hit.z) / kPeriod;
    return true;
  }

  // Analytic derivatives at the centre of pixel (x, y), by central differences of the exact map
  // over 1/64 px (the map is smooth there; the truncation error is ~1e-9 of the value).
  bool derivatives(int x, int y, glm::dvec2& uv, glm::dvec2& ddx, glm::dvec2& ddy) const {
    const double cx = x + 0.5, cy = y + 0.5, h = 1.0 / 64;
    glm::dvec2 l, r, u, d;
    if (!uvAt(cx, cy, uv) || !uvAt(cx - h, cy, l) || !uvAt(cx + h, cy, r) ||
        !uvAt(cx, cy - h, u) || !uvAt(cx, cy + h, d))
      return false;
    ddx = (r - l) / (2 * h);
    ddy = (d - u) / (2 * h);
    return true;
  }
};

double expectedLod(glm::dvec2 ddx, glm::dvec2 ddy) {
  const double rho = std::max(glm::length(ddx), glm::length(ddy)) * kTextureSize;
  return std::clamp(std::log2(rho), 0.0, 6.0);
}

// The shader with derivatives supplied by hand, as the pipeline's 2x2 quads will supply them:
// every pixel of the plane chooses log2 of its footprint, which spans magnification near the
// camera to the last level at the horizon.
TEST(TexturedPlane, ShaderSelectsTheFootprintsLevel) {
  const Texture texture = levelRampTexture();
  const TexturedShader shader{TextureSampler(texture, {})};
  const PlaneView view;
  double lowest = 10, highest = -1;
  int pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      glm::dvec2 uv, ddx, ddy;
      if (!view.derivatives(x, y, uv, ddx, ddy)) continue;
      Fragment<2> f;
      f.varyings = {float(uv.x), float(uv.y)};
      f.ddx = {float(ddx.x), float(ddx.y)};
      f.ddy = {float(ddy.x), float(ddy.y)};
      f.x = x;
      f.y = y;
      const double lod = expectedLod(ddx, ddy);
      ASSERT_NEAR(shader(f).color.r * 8.0, lod, 1e-5) << x << ", " << y;
      lowest = std::min(lowest, lod);
      highest = std::max(highest, lod);
      ++pixels;
    }
  EXPECT_GT(pixels, kWidth * kHeight / 3);
  EXPECT_EQ(lowest, 0.0);   // magnified near the camera...
  EXPECT_EQ(highest, 6.0);  // ...down to 1x1 at the horizon
}

// A checkerboard far away averages to grey through the mip chain; sampled at level 0 (no
// footprint) it aliases to its two colours. This is what the derivatives are for.
TEST(TexturedPlane, FootprintFiltersTheCheckerboardToItsMean) {
  Texture board;
  ASSERT_TRUE(checkerboardTexture(kTextureSize, 8, glm::vec4(1), glm::vec4(0, 0, 0, 1), board));
  const TextureSampler sampler(board, {});
  const TextureSampler unfilteredSampler(board, {TextureFilter::Nearest, AddressMode::Repeat,
                                                 AddressMode::Repeat});
  const PlaneView view;
  int far = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      glm::dvec2 uv, ddx, ddy;
      if (!view.derivatives(x, y, uv, ddx, ddy) || expectedLod(ddx, ddy) < 5.5) continue;
      ++far;
      const glm::vec2 fuv(uv);
      EXPECT_NEAR(sampler.sampleGrad(fuv, glm::vec2(ddx), glm::vec2(ddy)).r, 0.5f, 0.05f);
      const float unfiltered = unfilteredSampler.sample(fuv, 0.0f).r;
      EXPECT_TRUE(unfiltered == 0.0f || unfiltered == 1.0f);
    }
  EXPECT_GT(far, 50);
}

// The same plane drawn by the pipeline. Needs the derivatives the 2x2 quads fill in
// (Fragment::ddx, ddy for kDerivatives shaders): until then every fragment sees a zero footprint
// and the test skips itself. With them, each pixel's level must lie between the levels of the
// footprints a quad can measure: fine derivatives (the pixel's own row or column of its quad)
// or coarse ones (the quad's top row and left column), all from the exact map at the quad's
// pixel centres; the slack is 0.02 levels plus one RGBA8 step (8/255 levels).
TEST(TexturedPlane, PipelineDerivativesSelectMipLevels) {
  const Texture texture = levelRampTexture();
  const TexturedShader shader{TextureSampler(texture, {})};
  const std::vector<TexturedVertex> vertices = {
      {{-kHalfX, 0, kNearZ}, {-kHalfX / kPeriod, kNearZ / kPeriod}},
      {{kHalfX, 0, kNearZ}, {kHalfX / kPeriod, kNearZ / kPeriod}},
      {{kHalfX, 0, kFarZ}, {kHalfX / kPeriod, kFarZ / kPeriod}},
      {{-kHalfX, 0, kFarZ}, {-kHalfX / kPeriod, kFarZ / kPeriod}}};
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
  const TexturedVertexShader vs{planeCamera().viewProjection(float(kWidth) / kHeight)};
  PipelineState state;
  state.viewport = {0, 0, kWidth, kHeight};
  Framebuffer fb(kWidth, kHeight);
  fb.clear(glm::vec4(0, 0, 1, 1), 1.0f);
  PipelineStatistics stats;
  ASSERT_TRUE(draw(fb, state, DrawCall<TexturedVertexShader, TexturedShader>{vertices, indices, vs, shader},
                   stats));
  ASSERT_GT(stats.fragmentsWritten, uint64_t(kWidth * kHeight / 3));
  bool anyAboveLevel0 = false;
  for (PackedColor c : fb.colorPlane()) anyAboveLevel0 |= (c & 0xFFFF00u) == 0 && (c & 255u) > 0;
  ASSERT_TRUE(anyAboveLevel0) << "every pixel sampled level 0: are Fragment::ddx/ddy filled?";

  const PlaneView view;
  int checked = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int qx = x & ~1, qy = y & ~1;
      glm::dvec2 q[2][2];
      bool inside = true;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) inside &= view.uvAt(qx + i + 0.5, qy + j + 0.5, q[j][i]);
      if (!inside) continue;  // a quad with a pixel off the plane: helper lanes extrapolate
      const int ix = x - qx, iy = y - qy;
      const double fine = expectedLod(q[iy][1] - q[iy][0], q[1][ix] - q[0][ix]);
      const double coarse = expectedLod(q[0][1] - q[0][0], q[1][0] - q[0][0]);
      const double measured = (fb.color(x, y) & 255u) / 255.0 * 8.0;
      const double slack = 0.02 + 8.0 / 255.0;
      ASSERT_GE(measured, std::min(fine, coarse) - slack) << x << ", " << y;
      ASSERT_LE(measured, std::max(fine, coarse) + slack) << x << ", " << y;
      ++checked;
    }
  EXPECT_GT(checked, kWidth * kHeight / 3);
}

}  // namespace
}  // namespace rast
