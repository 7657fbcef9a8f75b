// Shadow-mapped Blinn-Phong rendering of a Scene: the light pass (a depth-only draw of every
// object from the light into its own Framebuffer) and the camera pass (shaders_cpp/blinn_phong.h
// reading that depth plane through a ShadowMap).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "pipeline/execution.h"
#include "pipeline/framebuffer.h"
#include "pipeline/state.h"
#include "pipeline/statistics.h"
#include "scene/scene.h"
#include "shaders_cpp/blinn_phong.h"

namespace rast {

struct ShadowSettings {
  int mapSize = 2048;        // square shadow map, texels per side
  // Tuned on the default scene against shadow rays (tests/blinn_phong_reference_test.cpp): at
  // 1024 texels 2e-4 / 0.02 left acne on the bunny (1.6 % of pixels off), 5e-4 / 0.05 0.7 %.
  float depthBias = 5e-4f;     // window-depth units of the light pass (shadow_map.h)
  float normalOffset = 0.05f;  // world units (ShadowVertexShader)
  int pcf = 3;               // 1, 3 or 5
};

// The light's view-projection fitted to an axis-aligned box (OpenGL clip conventions, so a
// light pass is an ordinary draw). Directional: an orthographic box around it along the light
// direction. Point: a perspective frustum from the light, aimed at the mean direction of the
// box's corners and fitted (off-centre) to their projections; an error if a corner is not in
// front of the light (the light inside or beside the box needs more than one map).
Status fitLightViewProjection(const Light& light, glm::vec3 boxMin, glm::vec3 boxMax,
                              glm::mat4& out);

// The scene's point light (Scene::lightPosition, white, ambient 0.08, as the Lambert mode).
Light sceneLight(const Scene& scene);
// World-space bounds of every object.
void sceneBounds(const Scene& scene, glm::vec3& boxMin, glm::vec3& boxMax);

// The light pass: `shadowMap` (mapSize x mapSize) cleared to depth 1, then every object drawn
// depth-only (colour writes off, no culling, CompareOp::Less) through lightViewProjection.
Status renderShadowMap(const Scene& scene, const glm::mat4& lightViewProjection,
                       Framebuffer& shadowMap, PipelineStatistics& stats,
                       const ExecutionOptions& exec = {});

// ShadingMode::BlinnPhong: fits the light to the scene bounds, runs the light pass, clears `fb`
// as renderScene does and draws every object with BlinnPhongShader (its albedo, specular 0.3,
// shininess 32). Statistics of both passes are added to `stats`.
Status renderSceneBlinnPhong(const Scene& scene, Framebuffer& fb, const PipelineState& state,
                             PipelineStatistics& stats, const ExecutionOptions& exec = {},
                             const ShadowSettings& shadows = {});

}  // namespace rast
