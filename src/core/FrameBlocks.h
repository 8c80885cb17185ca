#pragma once
// The per-frame uniform blocks (shaders/shared/Frame.h, Shadow.h) filled from the core's inputs.
// Penumbra's own renderer fills its G-buffer and lit passes' frame block with the same function.
#include "shared/Frame.h"
#include "shared/Shadow.h"

#include <penumbra/Scene.h>
#include <penumbra/ShadowViews.h>
#include <penumbra/Shadows.h>

namespace penumbra::core {

/// One light as the shaders read it (its kind, direction, position, radiance, cone and range).
gpu::LightGpu lightGpu(const Light& light);
/// The camera, the shadowing light, the screen and how to unproject the depth texture.
gpu::FrameUniforms frameUniforms(const ShadowCamera& camera, const Light& light, glm::ivec2 screen, int frameIndex,
                                 float sceneRadiusM);
/// The light's views. Throws penumbra::Error for a projection that made 0 or too many views.
gpu::ShadowUniforms shadowUniforms(const LightFrusta& frusta, int mapSize);

}  // namespace penumbra::core
