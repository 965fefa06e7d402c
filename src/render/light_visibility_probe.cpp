#include "render/light_visibility_probe.h"

#include "render/renderer.h"

#include <algorithm>
#include <cmath>

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

} // namespace pt
