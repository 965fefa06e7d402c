#include "lights/light_table.h"

#include "lights/light_entry.h"

#include <algorithm>
#include <cmath>

namespace pt {
namespace {

// selectionWeight's floor, relative to the colour's channel sum. For a non-negative colour the
// luminance is at least 0.0722 of that sum, so the floor never acts there; it acts on colours
// with a negative channel, whose luminance can be
// zero or negative while they still carry energy: they keep a small positive weight instead of
// one that would stall or break the CDF.
constexpr double kSelectionWeightFloor = 1e-3;

} // namespace

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

double selectionWeight(const glm::vec3& c) {
    return std::max<double>(luminance(c), kSelectionWeightFloor * (c.x + c.y + c.z));
}

double lambertianEmitterPower(const Material& m, double area) {
    return std::numbers::pi * selectionWeight(m.emission) * area * (m.doubleSided ? 2.0 : 1.0);
}

std::optional<LightEntry> areaEmitter(uint32_t type, uint32_t index, float samplingArea, double power) {
    if (!(power > 0.0) || !std::isfinite(power)) return std::nullopt;
    LightEntry e{};
    e.light.type = type;
    e.light.primitive = index;
    e.light.area = samplingArea;
    e.power = power;
    return e;
}

namespace {

void addEntry(const LightEntry& entry, LightTable& table, std::vector<double>& power) {
    table.lights.push_back(entry.light);
    power.push_back(entry.power);
    table.totalPower += entry.power;
}

// Emissive triangles or spheres: each gets its entry (or NO_LIGHT) in its lightIndex.
template <class Primitive, class MakeEntry>
void addPrimitiveEmitters(std::span<Primitive> primitives, std::span<const Material> materials, MakeEntry makeEntry,
    LightTable& table, std::vector<double>& power) {
    for (uint32_t i = 0; i < primitives.size(); ++i) {
        Primitive& primitive = primitives[i];
        primitive.lightIndex = NO_LIGHT;
        if (auto entry = makeEntry(primitive, i, materials[primitive.materialIndex])) {
            primitive.lightIndex = static_cast<uint32_t>(table.lights.size());
            addEntry(*entry, table, power);
        }
    }
}

} // namespace

LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<gpu::GpuSphere> spheres,
    std::span<const PunctualLight> punctual, std::span<const Material> materials, float sceneRadius,
    double environmentRadiance, const std::function<glm::vec3(uint32_t)>& triangleEmission) {
    LightTable table;
    std::vector<double> power;
    addPrimitiveEmitters(
        triangles, materials,
        [&](const gpu::GpuTriangle& tri, uint32_t index, const Material& m) {
            return triangleLight(tri, index, m, triangleEmission ? triangleEmission(index) : glm::vec3(1.0f));
        },
        table, power);
    addPrimitiveEmitters(spheres, materials, sphereLight, table, power);
    for (bool atInfinity : {false, true})
        for (const PunctualLight& pl : punctual)
            if ((pl.type == PunctualLight::Type::Directional) == atInfinity)
                if (auto entry = punctualLight(pl, sceneRadius)) addEntry(*entry, table, power);
    if (environmentRadiance >= 0.0) {
        table.environmentIndex = static_cast<uint32_t>(table.lights.size());
        addEntry(environmentLight(environmentRadiance, sceneRadius), table, power);
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
    table.power = std::move(power);
    return table;
}

float boundedLightShare(const LightTable& table) {
    for (size_t k = 0; k < table.lights.size(); ++k)
        if (table.lights[k].type == LIGHT_DIRECTIONAL || table.lights[k].type == LIGHT_ENVIRONMENT) return table.cdf[k];
    return 1.0f;
}

LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<const Material> materials) {
    return buildLightTable(triangles, {}, {}, materials, 1.0f);
}

} // namespace pt
