#include "lights/light_table.h"

#include <algorithm>
#include <cmath>

namespace pt {

namespace {
float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
} // namespace

LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<const Material> materials) {
    LightTable table;
    std::vector<double> power;
    for (uint32_t i = 0; i < triangles.size(); ++i) {
        gpu::GpuTriangle& tri = triangles[i];
        tri.lightIndex = NO_LIGHT;
        const Material& m = materials[tri.materialIndex];
        if (!m.emissive()) continue;
        const double area = 0.5 * glm::length(glm::dvec3(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
        // A colour with zero luminance (pure emission outside the weights) still needs a share.
        const double radiance = std::max<double>(luminance(m.emission), 1e-3 * (m.emission.x + m.emission.y + m.emission.z));
        const double p = radiance * area * (m.doubleSided ? 2.0 : 1.0);
        if (!(area > 0.0) || !(p > 0.0) || !std::isfinite(p)) continue;
        tri.lightIndex = static_cast<uint32_t>(table.lights.size());
        table.lights.push_back({i, 0.0f, static_cast<float>(area), 0.0f});
        power.push_back(p);
        table.totalPower += p;
    }
    table.cdf.assign(1, 0.0f);
    if (table.lights.empty()) return table;
    double running = 0;
    for (size_t k = 0; k < table.lights.size(); ++k) {
        running += power[k];
        table.cdf.push_back(static_cast<float>(running / table.totalPower));
    }
    table.cdf.back() = 1.0f; // exact end, whatever the rounding
    // The pmf is exactly what the kernel's CDF search selects with, so light-sampling pdfs and
    // the pdfs MIS computes for BSDF hits agree to the last bit.
    for (size_t k = 0; k < table.lights.size(); ++k) table.lights[k].pmf = table.cdf[k + 1] - table.cdf[k];
    return table;
}

} // namespace pt
