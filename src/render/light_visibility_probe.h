#pragma once

#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

#include <optional>

namespace pt {

// How often light sampling at the surfaces a camera sees finds its light unoccluded: a few
// samples per pixel of a small image, each taking one light sample at the camera ray's hit
// (DEBUG_VIEW_LIGHT_VISIBILITY, shaders/integrator/debug_view.glsl), of every kind of light: a
// room lit by the sky through a window is as hard as one lit through a door. Absent where no
// sample could be taken (no light
// faces a surface the camera sees). Deterministic: fixed size, samples and seed.
// `width` and `height`: the render's, whose aspect the probe keeps.
std::optional<float> probeLightVisibility(VulkanContext& context, const FlatScene& scene,
    const IntegratorSettings& settings, const Camera& camera, int width, int height);

} // namespace pt
