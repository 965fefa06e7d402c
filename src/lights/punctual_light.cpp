// Lights without geometry (shaders/lights/punctual_light.glsl): point, spot, the course's square
// lights and directional lights. Light sampling is their only way in.
#include "lights/light_entry.h"

#include <cmath>

namespace pt {

std::optional<LightEntry> punctualLight(const PunctualLight& pl, float sceneRadius) {
    LightEntry e{};
    gpu::GpuLight& light = e.light;
    double p = 0;
    if (pl.type == PunctualLight::Type::Point) {
        light.type = LIGHT_POINT;
        light.position = pl.position;
        p = 4.0 * std::numbers::pi * selectionWeight(pl.intensity);
    } else if (pl.type == PunctualLight::Type::Spot) {
        light.type = LIGHT_SPOT;
        light.position = pl.position;
        light.direction = glm::normalize(pl.direction);
        light.cosFalloff = pl.cosFalloff;
        light.cosCoverage = pl.cosCoverage;
        light.area = pl.falloffExponent; // unused by spots otherwise (see GpuLight)
        // Power of the cone out to the mid-point of the falloff band.
        p = 2.0 * std::numbers::pi * (1.0 - 0.5 * (double(pl.cosFalloff) + pl.cosCoverage)) *
            selectionWeight(pl.intensity);
    } else if (pl.type == PunctualLight::Type::Square) {
        light.type = LIGHT_SQUARE;
        light.position = pl.position;
        light.direction = glm::normalize(pl.direction);
        light.radius = pl.size;
        light.area = pl.size * pl.size;
        p = 2.0 * std::numbers::pi * selectionWeight(pl.intensity) * double(pl.size) * pl.size; // both faces
    } else {
        light.type = LIGHT_DIRECTIONAL;
        light.direction = glm::normalize(pl.direction);
        // The power reaching a disc the size of the scene, as pbrt estimates it.
        p = std::numbers::pi * double(sceneRadius) * sceneRadius * selectionWeight(pl.intensity);
    }
    light.intensity = pl.intensity;
    if (!(p > 0.0) || !std::isfinite(p)) return std::nullopt;
    e.power = p;
    return e;
}

} // namespace pt
