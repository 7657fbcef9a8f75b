// Textures and samplers (pipeline/texture.h, pipeline/sampler.h): exact texel values at texel
// centres, mip chain sizes, trilinear level selection, addressing modes, loading and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <OpenImageIO/imageio.h>

#include "pipeline/sampler.h"
#include "pipeline/texture.h"

namespace rast {
namespace {

constexpr TextureFilter kFilters[] = {TextureFilter::Nearest, TextureFilter::Bilinear,
                                      TextureFilter::Trilinear};
constexpr AddressMode kModes[] = {AddressMode::Repeat, AddressMode::ClampToEdge,
                                  AddressMode::MirrorRepeat};

// Texel (i, j) of an 8x4 texture: every channel a distinct dyadic value.
glm::vec4 distinctTexel(int i, int j) {
  return {float(i) / 8.0f, float(j) / 4.0f, float(i * 4 + j) / 32.0f, 1.0f - float(i + j) / 16.0f};
}

Texture distinctTexture() {
  std::vector<glm::vec4> texels;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i) texels.push_back(distinctTexel(i, j));
  Texture t;
  const Status s = Texture::fromPixels(8, 4, texels, t);
  EXPECT_TRUE(s) << s.message();
  return t;
}

TEST(Texture, TexelCentresReturnTexelsExactly) {
  const Texture t = distinctTexture();
  for (TextureFilter filter : kFilters)
    for (AddressMode mode : kModes) {
      const TextureSampler sampler(t, {filter, mode, mode});
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 8; ++i) {
          const glm::vec2 uv((i + 0.5f) / 8.0f, (j + 0.5f) / 4.0f);
          ASSERT_EQ(sampler.sample(uv, 0.0f), distinctTexel(i, j)) << i << ", " << j;
          // Magnification (lod < 0, zero footprint) is level 0 too.
          ASSERT_EQ(sampler.sample(uv, -2.5f), distinctTexel(i, j));
          ASSERT_EQ(sampler.sampleGrad(uv, glm::vec2(0), glm::vec2(0)), distinctTexel(i, j));
        }
    }
}

TEST(Texture, BilinearWeighsTheFourNearestTexels) {
  const Texture t = distinctTexture();
  const TextureSampler sampler(t, {TextureFilter::Bilinear, AddressMode::Repeat,
                                   AddressMode::Repeat});
  // Halfway between texels (2, 1), (3, 1), (2, 2), (3, 2), a quarter of the way in x.
  const glm::vec2 uv((2.5f + 0.25f) / 8.0f, (1.5f + 0.5f) / 4.0f);
  const glm::vec4 expected = 0.375f * distinctTexel(2, 1) + 0.125f * distinctTexel(3, 1) +
                             0.375f * distinctTexel(2, 2) + 0.125f * distinctTexel(3, 2);
  EXPECT_EQ(sampler.sample(uv, 0.0f), expected);
}

TEST(Texture, MipChainSizesForNonPowerOfTwo) {
  struct Case {
    int w, h;
    std::vector<std::pair<int, int>> sizes;
  };
  const Case cases[] = {
      {5, 3, {{5, 3}, {2, 1}, {1, 1}}},
      {7, 1, {{7, 1}, {3, 1}, {1, 1}}},
      {1, 9, {{1, 9}, {1, 4}, {1, 2}, {1, 1}}},
      {1, 1, {{1, 1}}},
      {640, 480, {{640, 480}, {320, 240}, {160, 120}, {80, 60}, {40, 30}, {20, 15}, {10, 7},
                  {5, 3}, {2, 1}, {1, 1}}},
      {33, 17, {{33, 17}, {16, 8}, {8, 4}, {4, 2}, {2, 1}, {1, 1}}},
  };
  for (const Case& c : cases) {
    ASSERT_EQ(mipLevelCount(c.w, c.h), int(c.sizes.size())) << c.w << "x" << c.h;
    Texture t;
    const std::vector<glm::vec4> texels(size_t(c.w) * c.h, glm::vec4(0.5f));
    ASSERT_TRUE(Texture::fromPixels(c.w, c.h, texels, t));
    ASSERT_EQ(t.levelCount(), int(c.sizes.size()));
    for (int k = 0; k < t.levelCount(); ++k) {
      EXPECT_EQ(t.level(k).width, c.sizes[k].first) << c.w << "x" << c.h << " level " << k;
      EXPECT_EQ(t.level(k).height, c.sizes[k].second) << c.w << "x" << c.h << " level " << k;
      EXPECT_EQ(t.level(k).texels.size(), size_t(c.sizes[k].first) * c.sizes[k].second);
      // The filter's weights sum to 1, so a constant image stays constant (to float rounding).
      for (const glm::vec4& v : t.level(k).texels)
        ASSERT_NEAR(v.r, 0.5f, 1e-6f) << c.w << "x" << c.h << " level " << k;
    }
  }
}

// A 2-texel checkerboard (0 and 1) filtered down: Blackman-Harris has no negative lobes, so no
// level rings outside [0, 1], and the levels smaller than the squares' period average to 1/2.
TEST(Texture, MipFilterNeitherRingsNorShiftsTheMean) {
  const int w = 24, h = 10;
  std::vector<glm::vec4> texels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) texels.push_back(glm::vec4(float((x / 2 + y / 2) % 2)));
  Texture t;
  ASSERT_TRUE(Texture::fromPixels(w, h, texels, t));
  for (int k = 1; k < t.levelCount(); ++k)
    for (const glm::vec4& v : t.level(k).texels) {
      ASSERT_GE(v.r, -1e-6f) << "level " << k;
      ASSERT_LE(v.r, 1.0f + 1e-6f) << "level " << k;
    }
  const TextureLevel& last = t.level(t.levelCount() - 1);
  EXPECT_NEAR(last.texels[0].r, 0.5f, 0.02f);
}

// Levels of distinct constant colours: the red channel of level k is k.
Texture levelRamp(int w, int h) {
  std::vector<TextureLevel> levels;
  for (int k = 0; k < mipLevelCount(w, h); ++k) {
    const int lw = mipLevelExtent(w, k), lh = mipLevelExtent(h, k);
    levels.push_back({lw, lh, std::vector<glm::vec4>(size_t(lw) * lh, glm::vec4(float(k), 0, 0, 1))});
  }
  Texture t;
  const Status s = Texture::fromLevels(std::move(levels), t);
  EXPECT_TRUE(s) << s.message();
  return t;
}

TEST(Texture, TrilinearLevelSelectionOnARamp) {
  const Texture t = levelRamp(16, 16);  // levels 0..4
  ASSERT_EQ(t.levelCount(), 5);
  const TextureSampler tri(t, {TextureFilter::Trilinear, AddressMode::Repeat, AddressMode::Repeat});
  const glm::vec2 uv(0.3f, 0.6f);
  // Exact blend weights for exact lods: (1 - f) * k + f * (k + 1) = k + f.
  for (float lod : {0.0f, 0.25f, 1.0f, 1.5f, 2.75f, 3.125f, 4.0f})
    EXPECT_EQ(tri.sample(uv, lod).r, lod) << lod;
  EXPECT_EQ(tri.sample(uv, 9.0f).r, 4.0f);   // clamped to the last level
  EXPECT_EQ(tri.sample(uv, -1.0f).r, 0.0f);  // and to level 0
  EXPECT_EQ(tri.sample(uv, std::numeric_limits<float>::quiet_NaN()).r, 0.0f);
  // Footprints of 2^k level-0 texels select level k exactly: |dUV/dx| * 16 = 4 -> lod 2.
  const float texel = 1.0f / 16.0f;
  EXPECT_EQ(tri.sampleGrad(uv, {4 * texel, 0}, {0, 0}).r, 2.0f);
  EXPECT_EQ(tri.sampleGrad(uv, {0, 0}, {0, 8 * texel}).r, 3.0f);
  EXPECT_EQ(tri.sampleGrad(uv, {texel, 0}, {0, 2 * texel}).r, 1.0f);      // the longer one
  EXPECT_EQ(tri.sampleGrad(uv, {-2 * texel, 0}, {0, 0.5f * texel}).r, 1.0f);  // sign-free
  // A diagonal footprint: |(3, 4)| = 5 texels, lod = log2(5), blended 0.3219 of the way to 3.
  EXPECT_NEAR(tri.sampleGrad(uv, {3 * texel, 4 * texel}, {0, 0}).r, std::log2(5.0), 1e-6);
  // Half a texel: lod -1, magnified from level 0.
  EXPECT_EQ(tri.sampleGrad(uv, {0.5f * texel, 0}, {0, 0.5f * texel}).r, 0.0f);

  // Nearest and Bilinear take the nearest level, halves up.
  for (TextureFilter f : {TextureFilter::Nearest, TextureFilter::Bilinear}) {
    const TextureSampler s(t, {f, AddressMode::Repeat, AddressMode::Repeat});
    EXPECT_EQ(s.sample(uv, 1.49f).r, 1.0f);
    EXPECT_EQ(s.sample(uv, 1.5f).r, 2.0f);
    EXPECT_EQ(s.sample(uv, 3.7f).r, 4.0f);
    EXPECT_EQ(s.sampleGrad(uv, {4 * texel, 0}, {0, 0}).r, 2.0f);
  }
}

TEST(Texture, LodUsesEachAxisSize) {
  // 16x4: a v step of 1/4 is one texel (lod 0), a u step of 1/4 four (lod 2).
  EXPECT_EQ(lodFromGradients({0, 0.25f}, {0, 0}, 16, 4), 0.0f);
  EXPECT_EQ(lodFromGradients({0.25f, 0}, {0, 0}, 16, 4), 2.0f);
  EXPECT_EQ(lodFromGradients({0, 0}, {0, 1.0f}, 16, 4), 2.0f);
  EXPECT_EQ(lodFromGradients({0, 0}, {0, 0}, 16, 4), -std::numeric_limits<float>::infinity());
}

// A 4x1 texture with red 10, 20, 30, 40 (and its 1x4 transpose for v).
float addressed(AddressMode mode, TextureFilter filter, float u, bool alongV = false) {
  std::vector<glm::vec4> texels;
  for (int i = 0; i < 4; ++i) texels.push_back(glm::vec4(float(10 * (i + 1)), 0, 0, 1));
  Texture t;
  EXPECT_TRUE(Texture::fromPixels(alongV ? 1 : 4, alongV ? 4 : 1, texels, t, false));
  const SamplerState state = alongV ? SamplerState{filter, AddressMode::Repeat, mode}
                                    : SamplerState{filter, mode, AddressMode::Repeat};
  const TextureSampler s(t, state);
  return s.sample(alongV ? glm::vec2(0.5f, u) : glm::vec2(u, 0.5f), 0.0f).r;
}

TEST(Texture, AddressModesOutsideTheUnitSquare) {
  struct Case {
    float u;
    float repeat, clamp, mirror;
  };
  // Nearest: texel index floor(4u); repeat wraps it mod 4, clamp to 0..3, mirror reflects with
  // period 8 (0 1 2 3 3 2 1 0).
  const Case nearest[] = {
      {-0.375f, 30, 10, 20},  // index -2
      {-0.125f, 40, 10, 10},  // -1
      {1.125f, 10, 40, 40},   // 4
      {1.625f, 30, 40, 20},   // 6
      {2.375f, 20, 40, 20},   // 9
      {-1.875f, 10, 10, 10},  // -8
      {0.875f, 40, 40, 40},   // 3: inside
  };
  for (bool alongV : {false, true})
    for (const Case& c : nearest) {
      EXPECT_EQ(addressed(AddressMode::Repeat, TextureFilter::Nearest, c.u, alongV), c.repeat) << c.u;
      EXPECT_EQ(addressed(AddressMode::ClampToEdge, TextureFilter::Nearest, c.u, alongV), c.clamp) << c.u;
      EXPECT_EQ(addressed(AddressMode::MirrorRepeat, TextureFilter::Nearest, c.u, alongV), c.mirror) << c.u;
    }
  // Bilinear: halfway between indices floor(4u - 0.5) and the next, each addressed.
  const Case bilinear[] = {
      {0.0f, 25, 10, 10},     // -1, 0
      {1.0f, 25, 40, 40},     // 3, 4
      {-0.25f, 35, 10, 15},   // -2, -1
      {1.5f, 25, 40, 25},     // 5, 6
  };
  for (bool alongV : {false, true})
    for (const Case& c : bilinear) {
      EXPECT_EQ(addressed(AddressMode::Repeat, TextureFilter::Bilinear, c.u, alongV), c.repeat) << c.u;
      EXPECT_EQ(addressed(AddressMode::ClampToEdge, TextureFilter::Bilinear, c.u, alongV), c.clamp) << c.u;
      EXPECT_EQ(addressed(AddressMode::MirrorRepeat, TextureFilter::Bilinear, c.u, alongV), c.mirror) << c.u;
    }
  // Far away and non-finite coordinates stay defined: reduced before any integer conversion.
  for (AddressMode m : kModes) {
    EXPECT_EQ(addressed(m, TextureFilter::Nearest, 1e30f), m == AddressMode::ClampToEdge ? 40 : 10);
    EXPECT_EQ(addressed(m, TextureFilter::Nearest, -1e30f), 10);
    EXPECT_EQ(addressed(m, TextureFilter::Nearest, std::numeric_limits<float>::quiet_NaN()), 10);
    EXPECT_EQ(addressed(m, TextureFilter::Nearest, std::numeric_limits<float>::infinity()), 10);
  }
}

// ---- Loading ----

std::string tempPath(const std::string& name) { return ::testing::TempDir() + "/texture_test_" + name; }

void writeImage(const std::string& path, int w, int h, int channels, OIIO::TypeDesc type,
                const void* data) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(w, h, channels, type);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // write the values as given, not un-premultiplied
  ASSERT_TRUE(out->open(path, spec));
  ASSERT_TRUE(out->write_image(type, data));
  ASSERT_TRUE(out->close());
}

double srgbToLinear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(TextureLoad, PngIsDecodedFromSrgbExceptAlpha) {
  const std::string path = tempPath("srgb.png");
  const uint8_t px[] = {0, 188, 255, 128, 10, 64, 200, 255};  // two RGBA pixels
  writeImage(path, 2, 1, 4, OIIO::TypeDesc::UINT8, px);
  Texture t;
  ASSERT_TRUE(loadTexture(path, t));
  ASSERT_EQ(t.width(), 2);
  ASSERT_EQ(t.height(), 1);
  for (int i = 0; i < 2; ++i) {
    const glm::vec4 v = t.level(0).at(i, 0);
    for (int c = 0; c < 3; ++c)
      // OpenImageIO's conversion is within 6e-6 of the formula (a fast pow), so 1e-5.
      EXPECT_NEAR(v[c], srgbToLinear(px[4 * i + c] / 255.0), 1e-5) << i << " " << c;
    EXPECT_NEAR(v.a, px[4 * i + 3] / 255.0, 1e-7);
  }
  // Taken as linear on request: the stored values / 255.
  ASSERT_TRUE(loadTexture(path, t, ColorEncoding::Linear));
  EXPECT_NEAR(t.level(0).at(0, 0).g, 188 / 255.0, 1e-7);
}

TEST(TextureLoad, ExrIsLinearFloatAndGreyIsReplicated) {
  const std::string path = tempPath("linear.exr");
  const float px[] = {0.25f, 2.0f, -0.5f, 0.125f, 1e-3f, 3.0f};  // two RGB pixels
  writeImage(path, 2, 1, 3, OIIO::TypeDesc::FLOAT, px);
  Texture t;
  ASSERT_TRUE(loadTexture(path, t));
  EXPECT_EQ(t.level(0).at(0, 0), glm::vec4(0.25f, 2.0f, -0.5f, 1.0f));
  EXPECT_EQ(t.level(0).at(1, 0), glm::vec4(0.125f, 1e-3f, 3.0f, 1.0f));
  EXPECT_EQ(t.levelCount(), 2);

  const std::string grey = tempPath("grey.exr");
  const float g[] = {0.5f, 0.75f, 0.25f, 1.5f};  // 2x2, grey
  writeImage(grey, 2, 2, 1, OIIO::TypeDesc::FLOAT, g);
  ASSERT_TRUE(loadTexture(grey, t));
  EXPECT_EQ(t.level(0).at(1, 1), glm::vec4(1.5f, 1.5f, 1.5f, 1.0f));
}

TEST(TextureLoad, ErrorsAreOneClearLine) {
  Texture t;
  auto expectError = [&](const std::string& path, const std::string& part) {
    const Status s = loadTexture(path, t);
    ASSERT_FALSE(s) << path;
    EXPECT_NE(s.message().find(path), std::string::npos) << s.message();
    EXPECT_NE(s.message().find(part), std::string::npos) << s.message();
    EXPECT_EQ(s.message().find('\n'), std::string::npos) << s.message();
  };
  expectError(tempPath("does_not_exist.png"), "no such file");
  expectError(::testing::TempDir(), "is a directory");

  const std::string text = tempPath("notes.txt");
  std::ofstream(text) << "not an image\n";
  expectError(text, "not an image format");
  const std::string fake = tempPath("fake.png");
  std::ofstream(fake) << "PNG? no.\n";
  expectError(fake, "not an image format");

  const std::string five = tempPath("five.exr");
  const float px[5] = {0, 0, 0, 0, 0};
  writeImage(five, 1, 1, 5, OIIO::TypeDesc::FLOAT, px);
  expectError(five, "5 channels");

  const std::string nan = tempPath("nan.exr");
  const float bad[3] = {0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f};
  writeImage(nan, 1, 1, 3, OIIO::TypeDesc::FLOAT, bad);
  expectError(nan, "not finite");
}

TEST(TextureLoad, BadPixelsInMemoryAreErrors) {
  Texture t;
  const std::vector<glm::vec4> three(3, glm::vec4(0));
  EXPECT_FALSE(Texture::fromPixels(2, 2, three, t));
  EXPECT_FALSE(Texture::fromPixels(0, 3, {}, t));
  EXPECT_FALSE(Texture::fromPixels(kMaxTextureSize + 1, 1, three, t));
  std::vector<TextureLevel> wrong = {{4, 4, std::vector<glm::vec4>(16)}, {3, 2, std::vector<glm::vec4>(6)}};
  const Status s = Texture::fromLevels(wrong, t);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("expected 2x2"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace rast
