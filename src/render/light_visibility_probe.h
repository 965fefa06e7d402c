#pragma once

#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

#include <optional>
#include <string>

namespace pt {

// How often light sampling at the surfaces a camera sees finds its light unoccluded: a few
// samples per pixel of a small image, each taking one light sample at the camera ray's hit
// (DEBUG_VIEW_LIGHT_VISIBILITY, shaders/integrator/debug_view.glsl). Lights at infinity (the
// sky, directional lights) are left out: their light subpaths start on a disc around the whole
// scene, most of them far from where they are needed, and BDPT did not pay on the one such scene
// measured (a room lit by daylight through a door ajar). Absent where no sample could be taken
// (no light faces a surface the camera sees). Deterministic: fixed size, samples and seed.
// `width` and `height`: the render's, whose aspect the probe keeps.
struct LightVisibilityProbe {
    std::optional<float> lightVisibility;
    // The fraction of cosine-weighted bounces from the same surfaces that meet a lit sharp GGX
    // lobe (FlatScene::glossyCausticBounces).
    std::optional<float> glossyCausticBounces;
    // The median distance to the surfaces the camera sees that sample lights (FlatScene::cameraHitDistance).
    std::optional<float> cameraHitDistance;
};
LightVisibilityProbe probeLightVisibility(VulkanContext& context, const FlatScene& scene,
    const IntegratorSettings& settings, const Camera& camera, int width, int height);

// What `--integrator auto` (and vertex merging's radius) needs before it decides (pt render and pt
// view alike): where BDPT could render the scene, the probe's measurements, stored in
// scene.lightVisibility and scene.cameraHitDistance for computeFeatures and the renderer;
// otherwise both are cleared. Returns the line to log ("integrator auto: ..."), empty where
// nothing was measured for auto.
std::string measureForAutoIntegrator(VulkanContext& context, FlatScene& scene, const IntegratorSettings& settings,
    const Camera& camera, int width, int height);

} // namespace pt
