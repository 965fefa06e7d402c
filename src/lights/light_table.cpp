#include "lights/light_table.h"

#include <algorithm>
#include <cmath>

namespace pt {
namespace {

constexpr double kPi = 3.14159265358979323846;


// Rows of the GpuSphere maps back into a matrix (the linear part is all we need).
glm::dmat3 linearPart(const glm::vec4 rows[3]) {
    glm::dmat3 m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m[c][r] = rows[r][c];
    return m;
}

// A sphere is "round" when its linear map is a rotation times a uniform scale: then it is
// sampled by the cone of directions it subtends. Ellipsoids are sampled by area.
bool roundRadius(const glm::dmat3& a, double& radius) {
    const glm::dmat3 ata = glm::transpose(a) * a;
    const double s2 = (ata[0][0] + ata[1][1] + ata[2][2]) / 3.0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (std::abs(ata[c][r] - (r == c ? s2 : 0.0)) > 1e-5 * s2) return false;
    radius = std::sqrt(s2);
    return true;
}

} // namespace

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

double selectionWeight(const glm::vec3& c) { return std::max<double>(luminance(c), 1e-3 * (c.x + c.y + c.z)); }

LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<gpu::GpuSphere> spheres,
    std::span<const PunctualLight> punctual, std::span<const Material> materials, float sceneRadius,
    double environmentRadiance) {
    LightTable table;
    std::vector<double> power;
    auto add = [&](const gpu::GpuLight& light, double p) {
        table.lights.push_back(light);
        power.push_back(p);
        table.totalPower += p;
    };
    // Power of a Lambertian emitter: pi x radiance x area (x2 when it emits from both sides).
    for (uint32_t i = 0; i < triangles.size(); ++i) {
        gpu::GpuTriangle& tri = triangles[i];
        tri.lightIndex = NO_LIGHT;
        const Material& m = materials[tri.materialIndex];
        if (!m.emissive()) continue;
        const double area = 0.5 * glm::length(glm::dvec3(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
        const double p = kPi * selectionWeight(m.emission) * area * (m.doubleSided ? 2.0 : 1.0);
        if (!(area > 0.0) || !(p > 0.0) || !std::isfinite(p)) continue;
        tri.lightIndex = static_cast<uint32_t>(table.lights.size());
        gpu::GpuLight light{};
        light.type = LIGHT_TRIANGLE;
        light.primitive = i;
        light.area = static_cast<float>(area);
        add(light, p);
    }
    for (uint32_t i = 0; i < spheres.size(); ++i) {
        gpu::GpuSphere& sphere = spheres[i];
        sphere.lightIndex = NO_LIGHT;
        const Material& m = materials[sphere.materialIndex];
        if (!m.emissive()) continue;
        const glm::dmat3 a = linearPart(sphere.objectToWorld);
        const double det = std::abs(glm::determinant(a));
        // Area estimate for the power only: 4 pi times the squared geometric-mean radius.
        const double area = 4.0 * kPi * std::pow(det, 2.0 / 3.0);
        const double p = kPi * selectionWeight(m.emission) * area * (m.doubleSided ? 2.0 : 1.0);
        if (!(det > 0.0) || !(p > 0.0) || !std::isfinite(p)) continue;
        sphere.lightIndex = static_cast<uint32_t>(table.lights.size());
        gpu::GpuLight light{};
        light.type = LIGHT_SPHERE;
        light.primitive = i;
        light.area = static_cast<float>(det);
        light.position = glm::vec3(sphere.objectToWorld[0].w, sphere.objectToWorld[1].w, sphere.objectToWorld[2].w);
        double radius = 0.0;
        // Double-sided spheres are lit from inside too: area sampling covers both cases.
        if (!m.doubleSided && roundRadius(a, radius)) light.radius = static_cast<float>(radius);
        add(light, p);
    }
    for (const PunctualLight& pl : punctual) {
        gpu::GpuLight light{};
        double p = 0;
        if (pl.type == PunctualLight::Type::Point) {
            light.type = LIGHT_POINT;
            light.position = pl.position;
            p = 4.0 * kPi * selectionWeight(pl.intensity);
        } else if (pl.type == PunctualLight::Type::Spot) {
            light.type = LIGHT_SPOT;
            light.position = pl.position;
            light.direction = glm::normalize(pl.direction);
            light.cosFalloff = pl.cosFalloff;
            light.cosCoverage = pl.cosCoverage;
            light.area = pl.falloffExponent; // unused by spots otherwise (see GpuLight)
            // Power of the cone out to the mid-point of the falloff band.
            p = 2.0 * kPi * (1.0 - 0.5 * (double(pl.cosFalloff) + pl.cosCoverage)) * selectionWeight(pl.intensity);
        } else if (pl.type == PunctualLight::Type::Square) {
            light.type = LIGHT_SQUARE;
            light.position = pl.position;
            light.direction = glm::normalize(pl.direction);
            light.radius = pl.size;
            light.area = pl.size * pl.size;
            p = 2.0 * kPi * selectionWeight(pl.intensity) * double(pl.size) * pl.size; // both faces
        } else {
            light.type = LIGHT_DIRECTIONAL;
            light.direction = glm::normalize(pl.direction);
            // The power reaching a disc the size of the scene, as pbrt estimates it.
            p = kPi * double(sceneRadius) * sceneRadius * selectionWeight(pl.intensity);
        }
        light.intensity = pl.intensity;
        if (!(p > 0.0) || !std::isfinite(p)) continue;
        add(light, p);
    }

    if (environmentRadiance >= 0.0) {
        // The power it sends through a disc the size of the scene: pi R^2 x (pi x average radiance).
        const double p = kPi * double(sceneRadius) * sceneRadius * kPi * std::max(environmentRadiance, 1e-6);
        gpu::GpuLight light{};
        light.type = LIGHT_ENVIRONMENT;
        table.environmentIndex = static_cast<uint32_t>(table.lights.size());
        add(light, p);
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

LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<const Material> materials) {
    return buildLightTable(triangles, {}, {}, materials, 1.0f);
}

} // namespace pt
