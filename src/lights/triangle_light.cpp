// Emissive triangles, sampled by area (shaders/lights/triangle_light.glsl).
#include "lights/light_entry.h"

#include <cmath>

namespace pt {

std::optional<LightEntry> triangleLight(const gpu::GpuTriangle& tri, uint32_t index, const Material& m) {
    if (!m.emissive()) return std::nullopt;
    // Power of a Lambertian emitter: pi x radiance x area (x2 when it emits from both sides).
    const double area = 0.5 * glm::length(glm::dvec3(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
    const double p = kLightPi * selectionWeight(m.emission) * area * (m.doubleSided ? 2.0 : 1.0);
    if (!(area > 0.0) || !(p > 0.0) || !std::isfinite(p)) return std::nullopt;
    LightEntry e{};
    e.light.type = LIGHT_TRIANGLE;
    e.light.primitive = index;
    e.light.area = static_cast<float>(area);
    e.power = p;
    return e;
}

} // namespace pt
