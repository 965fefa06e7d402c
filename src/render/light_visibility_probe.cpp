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

LightVisibilityProbe probeLightVisibility(VulkanContext& context, const FlatScene& scene,
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
    std::vector<float> distances;
    for (size_t i = 0; i < r.mean.rgba.size(); i += 4) {
        visible += r.mean.rgba[i];
        attempted += r.mean.rgba[i + 1];
        if (r.mean.rgba[i + 2] > 0.0f) distances.push_back(r.mean.rgba[i + 2]);
    }
    LightVisibilityProbe probe;
    if (attempted > 0) probe.lightVisibility = float(visible / attempted);
    if (!distances.empty()) {
        std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
        probe.cameraHitDistance = distances[distances.size() / 2];
    }
    return probe;
}

std::string measureForAutoIntegrator(VulkanContext& context, FlatScene& scene, const IntegratorSettings& settings,
    const Camera& camera, int width, int height) {
    scene.lightVisibility.reset();
    scene.cameraHitDistance.reset();
    IntegratorSettings bidirectional = settings;
    bidirectional.estimator = Estimator::Bidirectional;
    const bool merging = settings.estimator == Estimator::VertexMerging;
    if ((settings.estimator != Estimator::Auto && !merging) || !computeFeatures(scene, bidirectional).bdpt) return "";
    const LightVisibilityProbe probe = probeLightVisibility(context, scene, settings, camera, width, height);
    scene.lightVisibility = probe.lightVisibility;
    scene.cameraHitDistance = probe.cameraHitDistance;
    if (!scene.lightVisibility || merging) return "";
    char line[160];
    std::snprintf(line, sizeof line, "integrator auto: %.1f%% of light samples find their light (BDPT below %.0f%%)",
        100.0 * *scene.lightVisibility, 100.0 * kBdptBelowLightVisibility);
    return line;
}

} // namespace pt
