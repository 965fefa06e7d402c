#include "render/light_visibility_probe.h"

#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pt {

namespace {
// 64 pixels across at the camera's aspect, 4 samples each: ~10^4 light samples, enough to tell
// 2% from 20% (the rule's scale, flatten/feature_set.cpp) in a fraction of a second.
constexpr int kProbeWidth = 64;
constexpr uint32_t kProbeSpp = 4;
// A pixel's red sum holds two counts (shared/layout.h): each must stay below the radix.
static_assert(kProbeSpp < LIGHT_VIA_SHARP_LOBE);
} // namespace

LightVisibilityProbe probeLightVisibility(VulkanContext& context, const FlatScene& scene,
    const IntegratorSettings& settings, const Camera& camera, int width, int height) {
    IntegratorSettings s = settings;
    s.estimator = Estimator::Path;
    s.seed = 0;
    FeatureSet f = computeFeatures(scene, s);
    f.lightTracing = f.bdpt = false;
    f.debugView = DEBUG_VIEW_LIGHT_VISIBILITY;
    // The tree, even for a tiny scene: 4 samples of a small image do not repay the 2 s that
    // lavapipe takes to compile every triangle's test inline (the probe measures the same either way).
    f.uniformTriangles = 0;
    const double aspect = double(width) / double(std::max(height, 1));
    const int probeHeight = std::clamp(int(std::lround(kProbeWidth / aspect)), 1, 4 * kProbeWidth);
    Renderer renderer(context, scene, f, s, camera, FilmSettings{kProbeWidth, probeHeight, glm::vec3(0.0f)});
    renderer.addSamples(kProbeSpp, 0);
    const Renderer::Readback r = renderer.read();
    double visible = 0, glossyCausticBounce = 0, attempted = 0;
    std::vector<float> distances;
    for (size_t i = 0; i < r.mean.rgba.size(); i += 4) {
        // Counts from the red sum: bounces that meet a lit sharp lobe times the radix, plus
        // samples that found their light (exact: small integers over the sample count).
        const double red = double(r.mean.rgba[i]) * kProbeSpp;
        const double behind = std::floor((red + 0.5) / LIGHT_VIA_SHARP_LOBE);
        glossyCausticBounce += behind / kProbeSpp;
        visible += (red - behind * LIGHT_VIA_SHARP_LOBE) / kProbeSpp;
        attempted += r.mean.rgba[i + 1];
        if (r.mean.rgba[i + 2] > 0.0f) distances.push_back(r.mean.rgba[i + 2]);
    }
    LightVisibilityProbe probe;
    if (attempted > 0) {
        probe.lightVisibility = float(visible / attempted);
        probe.glossyCausticBounces = float(glossyCausticBounce / attempted);
    }
    if (!distances.empty()) {
        std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
        probe.cameraHitDistance = distances[distances.size() / 2];
    }
    return probe;
}

std::string measureForAutoIntegrator(VulkanContext& context, FlatScene& scene, const IntegratorSettings& settings,
    const Camera& camera, int width, int height) {
    scene.lightVisibility.reset();
    scene.glossyCausticBounces.reset();
    scene.cameraHitDistance.reset();
    IntegratorSettings bidirectional = settings;
    bidirectional.estimator = Estimator::Bidirectional;
    const bool merging = settings.estimator == Estimator::VertexMerging;
    if ((settings.estimator != Estimator::Auto && !merging) || !computeFeatures(scene, bidirectional).bdpt) return "";
    const LightVisibilityProbe probe = probeLightVisibility(context, scene, settings, camera, width, height);
    scene.lightVisibility = probe.lightVisibility;
    scene.glossyCausticBounces = probe.glossyCausticBounces;
    scene.cameraHitDistance = probe.cameraHitDistance;
    if (!scene.lightVisibility || merging) return "";
    char line[224];
    std::snprintf(line, sizeof line,
        "integrator auto: %.1f%% of light samples find their light (BDPT below %.0f%%), %.1f%% of bounces meet a "
        "lit sharp lobe (BDPT from %.1f%%)",
        100.0 * *scene.lightVisibility, 100.0 * kBdptBelowLightVisibility,
        100.0 * scene.glossyCausticBounces.value_or(0.0f), 100.0 * kBdptFromGlossyCausticBounces);
    return line;
}

} // namespace pt
