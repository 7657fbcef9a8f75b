// The contract between the pipeline and C++ shaders.
//
// A vertex shader is a type with
//   using Vertex = ...;                      the user-defined input vertex type
//   static constexpr int kVaryings = N;      floats it passes on
//   ShadedVertex<N> operator()(const Vertex&) const;
// A pixel shader is a type with
//   static constexpr int kVaryings = M;      varyings it reads (M <= N): only these are interpolated
//   static constexpr bool kMayDiscard;       whether it can return PixelResult::discarded()
//   PixelResult operator()(const Fragment<M>&) const;
// and optionally
//   static constexpr bool kDerivatives = true;  run on 2x2 quads: Fragment::ddx/ddy are filled
//   static constexpr bool kPerTriangle = true;  the result depends on nothing but primitiveId and
//                                               frontFacing (and kVaryings == 0): run once per
//                                               triangle and tile, not per pixel
//   static constexpr bool kWholeRows = true;    safe on any input: it may also run on the lanes
//                                               of a tile row that no triangle covers (their
//                                               varyings extrapolated, even infinite or NaN),
//                                               whose results are thrown away; then it runs on
//                                               whole rows of eight lanes, which the compiler
//                                               vectorises (kMayDiscard and kDerivatives false)
//   static constexpr bool kSideEffects = true;  it writes something besides its result (a probe
//                                               that counts or records fragments): it runs once
//                                               per passing fragment, as the fragment passes.
//                                               Otherwise a tile may shade only the fragments it
//                                               keeps (tile_loop.h, ExecutionOptions::deferShading)
// Shaders are called through templates, so they inline into the stage loops.
#pragma once

#include <array>
#include <concepts>
#include <cstdint>
#include <glm/vec4.hpp>

namespace rast {

template <int N>
using Varyings = std::array<float, N>;

// Output of the vertex stage (and of the clipper): IN to clip, OUT of the vertex shader.
template <int N>
struct ShadedVertex {
  glm::vec4 position;  // clip space, or window space (see PositionSpace)
  Varyings<N> varyings{};
};

// Input of the pixel shader.
template <int N>
struct Fragment {
  Varyings<N> varyings;   // perspective-correct
  int x = 0, y = 0;       // pixel; its centre is (x + 0.5, y + 0.5)
  float depth = 0;        // window depth z/w in [0, 1]
  bool frontFacing = true;
  uint32_t primitiveId = 0;  // index of the triangle within its draw
  // Screen-space derivatives of each varying across the pixel's 2x2 quad (per pixel to the
  // right and down); zero unless the shader declares kDerivatives.
  Varyings<N> ddx{}, ddy{};
};

struct PixelResult {
  glm::vec4 color{0, 0, 0, 1};  // RGBA in [0, 1], clamped when written
  bool discard = false;

  static PixelResult discarded() { return {glm::vec4(0), true}; }
};

template <class VS>
concept VertexShader = requires(const VS& vs, const typename VS::Vertex& v) {
  { VS::kVaryings } -> std::convertible_to<int>;
  { vs(v) } -> std::same_as<ShadedVertex<VS::kVaryings>>;
};

template <class PS>
concept PixelShader = requires(const PS& ps, const Fragment<PS::kVaryings>& f) {
  { PS::kVaryings } -> std::convertible_to<int>;
  { PS::kMayDiscard } -> std::convertible_to<bool>;
  { ps(f) } -> std::same_as<PixelResult>;
};

}  // namespace rast
