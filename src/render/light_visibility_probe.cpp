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
} // namespace

std::optional<float> probeLightVisibility(VulkanContext& context, const FlatScene& scene,
    const IntegratorSettings& settings, const Camera& camera, int width, int height) {
    IntegratorSettings s = settings;
    s.estimator = Estimator::Path;
    s.seed = 0;
    FeatureSet f = computeFeatures(scene, s);
    f.lightTracing = f.bdpt = false;
    f.debugView = DEBUG_VIEW_LIGHT_VISIBILITY;
    const double aspect = double(width) / double(std::max(height, 1));
    const int probeHeight = std::clamp(int(std::lround(kProbeWidth / aspect)), 1, 4 * kProbeWidth);
    Renderer renderer(context, scene, f, s, camera, FilmSettings{kProbeWidth, probeHeight, glm::vec3(0.0f)});
    renderer.addSamples(kProbeSpp, 0);
    const Renderer::Readback r = renderer.read();
    double visible = 0, attempted = 0;
    for (size_t i = 0; i < r.mean.rgba.size(); i += 4) {
        visible += r.mean.rgba[i];
        attempted += r.mean.rgba[i + 1];
    }
    if (!(attempted > 0)) return std::nullopt;
    return float(visible / attempted);
}

std::string measureForAutoIntegrator(VulkanContext& context, FlatScene& scene, const IntegratorSettings& settings,
    const Camera& camera, int width, int height) {
    scene.lightVisibility.reset();
    IntegratorSettings bidirectional = settings;
    bidirectional.estimator = Estimator::Bidirectional;
    if (settings.estimator != Estimator::Auto || !computeFeatures(scene, bidirectional).bdpt) return "";
    scene.lightVisibility = probeLightVisibility(context, scene, settings, camera, width, height);
    if (!scene.lightVisibility) return "";
    char line[160];
    std::snprintf(line, sizeof line, "integrator auto: %.1f%% of light samples find their light (BDPT below %.0f%%)",
        100.0 * *scene.lightVisibility, 100.0 * kBdptBelowLightVisibility);
    return line;
}

} // namespace pt
