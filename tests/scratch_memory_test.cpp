// Memory kept between draws (pipeline/scratch_memory.h): blocks come back to the next draw, and
// nothing drawn depends on where the memory came from.
#include <gtest/gtest.h>

#include <cstring>

#include <glm/vec2.hpp>

#include "tests/window_draw.h"

namespace rast {
namespace {

TEST(ScratchMemory, SizeClassesReuseBlocksAndReleaseFreesThem) {
  ScratchMemory memory;
  void* small = memory.allocate(100);  // below kMinKept: not kept
  memory.deallocate(small, 100);
  EXPECT_EQ(memory.keptBytes(), 0u);

  void* a = memory.allocate(1 << 20);
  memory.deallocate(a, 1 << 20);
  EXPECT_EQ(memory.keptBytes(), size_t{1} << 20);
  // A slightly smaller request of the same class gets the same block back.
  void* b = memory.allocate((1 << 20) - 1000);
  EXPECT_EQ(b, a);
  EXPECT_EQ(memory.keptBytes(), 0u);
  memory.deallocate(b, (1 << 20) - 1000);
  EXPECT_EQ(memory.release(), size_t{1} << 20);
  EXPECT_EQ(memory.keptBytes(), 0u);
}

using testing_support::DrawnFrame;

// A W2-style grid of small triangles (many set-up chunks and bin entries), 640x360.
DrawnFrame drawGrid(ScratchMemory* memory, float z) {
  constexpr int kW = 640, kH = 360, kCell = 4;
  std::vector<WindowVertex> vertices;
  std::vector<uint32_t> indices;
  const int cols = kW / kCell + 1, rows = kH / kCell + 1;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i)
      vertices.push_back({glm::vec3(float(i * kCell), float(j * kCell), z)});
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      const uint32_t a = uint32_t(j * cols + i), b = a + 1, c = a + uint32_t(cols), d = c + 1;
      for (uint32_t v : {a, b, d, a, d, c}) indices.push_back(v);
    }
  ExecutionOptions exec;
  exec.memory = memory;
  return testing_support::drawWindowTriangles(kW, kH, vertices, indices,
                                              glm::vec4(0.25f, 0.5f, 0.75f, 1.0f), exec);
}

TEST(ScratchMemory, DrawsKeepTheirBlocksForTheNextDrawAndDrawTheSame) {
  const DrawnFrame plain = drawGrid(nullptr, 0.5f);
  EXPECT_EQ(plain.stats.fragmentsWritten, 640u * 360);

  ScratchMemory memory;
  const DrawnFrame first = drawGrid(&memory, 0.5f);
  const size_t kept = memory.keptBytes();
  // The set-up triangles alone: 28,800 of them.
  EXPECT_GT(kept, size_t{28800} * sizeof(SetupTriangle<0>));
  // The same draw again takes every block it needs from the kept ones and gives them back.
  const DrawnFrame second = drawGrid(&memory, 0.5f);
  EXPECT_EQ(memory.keptBytes(), kept);

  for (const DrawnFrame* f : {&first, &second}) {
    EXPECT_TRUE(f->color == plain.color);
    EXPECT_EQ(std::memcmp(f->depth.data(), plain.depth.data(), plain.depth.size() * sizeof(float)), 0);
    EXPECT_EQ(f->stats, plain.stats);
  }
}

}  // namespace
}  // namespace rast
