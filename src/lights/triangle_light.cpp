// Emissive triangles, sampled by area (shaders/lights/triangle_light.glsl).
#include "lights/light_entry.h"

#include <cmath>

namespace pt {

std::optional<LightEntry> triangleLight(
    const gpu::GpuTriangle& tri, uint32_t index, const Material& m, glm::vec3 textureAverage) {
    if (!m.emissive()) return std::nullopt;
    const double area = 0.5 * glm::length(glm::dvec3(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
    if (!(area > 0.0)) return std::nullopt;
    Material emitted = m;
    emitted.emission *= textureAverage; // the light it gives, not its factor's
    if (!emitted.emissive()) return std::nullopt;
    return areaEmitter(LIGHT_TRIANGLE, index, static_cast<float>(area), lambertianEmitterPower(emitted, area));
}

} // namespace pt
