// Emissive triangles, sampled by area or by solid angle (shaders/lights/triangle_light.glsl).
#include "lights/light_entry.h"
#include "lights/light_table.h"

#include <algorithm>
#include <cmath>
#include <vector>

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

namespace {

// Solid angle of the triangle seen from x (Van Oosterom and Strackee 1983), as the kernel computes it.
double solidAngle(const gpu::GpuTriangle& t, const glm::dvec3& x) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(t.p0) - x), b = glm::normalize(glm::dvec3(t.p1) - x),
                     c = glm::normalize(glm::dvec3(t.p2) - x);
    return 2.0 *
           std::atan2(std::abs(glm::dot(a, glm::cross(b, c))), 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a));
}

} // namespace

bool someReceiverSeesALargeTriangleLight(
    std::span<const gpu::GpuTriangle> triangles, size_t worldTriangles, size_t maxReceivers) {
    worldTriangles = std::min(worldTriangles, triangles.size());
    std::vector<const gpu::GpuTriangle*> emitters;
    size_t receivers = 0;
    for (size_t i = 0; i < worldTriangles; ++i) {
        if (triangles[i].lightIndex != NO_LIGHT)
            emitters.push_back(&triangles[i]);
        else
            ++receivers;
    }
    if (emitters.empty() || receivers == 0) return false;
    const size_t stride = std::max<size_t>(1, receivers / maxReceivers);
    size_t seen = 0;
    for (size_t i = 0; i < worldTriangles; ++i) {
        const gpu::GpuTriangle& r = triangles[i];
        if (r.lightIndex != NO_LIGHT || seen++ % stride != 0) continue;
        const glm::dvec3 centroid = (glm::dvec3(r.p0) + glm::dvec3(r.p1) + glm::dvec3(r.p2)) / 3.0;
        for (const gpu::GpuTriangle* e : emitters)
            if (solidAngle(*e, centroid) >= SPHERICAL_SAMPLING_MIN) return true;
    }
    return false;
}

} // namespace pt
