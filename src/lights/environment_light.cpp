// The environment (shaders/lights/environment_light.glsl), sampled by its luminance through the
// CDFs flattenScene builds.
#include "lights/light_entry.h"

#include <algorithm>

namespace pt {
namespace {

// A black environment still gets a tiny positive power: its entry stays in the table (the kernel
// finds it by LightTable::environmentIndex) and the CDF stays well-defined when it is the only
// light.
constexpr double kMinEnvironmentRadiance = 1e-6;

} // namespace

LightEntry environmentLight(double averageRadiance, float sceneRadius) {
    LightEntry e{};
    e.light.type = LIGHT_ENVIRONMENT;
    // The power it sends through a disc the size of the scene: pi R^2 x (pi x average radiance).
    e.power = std::numbers::pi * double(sceneRadius) * sceneRadius * std::numbers::pi *
              std::max(averageRadiance, kMinEnvironmentRadiance);
    return e;
}

} // namespace pt
