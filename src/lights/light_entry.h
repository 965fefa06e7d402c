#pragma once
// One entry of the light-selection table: what the kernel samples (GpuLight) and the power that
// light selection weighs it by. Each light type makes its entries in a file of its own, beside
// the shader that samples it (as pbrt-v4's Light::Phi sits with each light's sampling):
//   triangle_light.cpp    shaders/lights/triangle_light.glsl
//   sphere_light.cpp      shaders/lights/sphere_light.glsl
//   punctual_light.cpp    shaders/lights/punctual_light.glsl
//   environment_light.cpp shaders/lights/environment_light.glsl
#include "scene/scene.h"
#include "shared/layout.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <numbers>
#include <optional>

namespace pt {

struct LightEntry {
    gpu::GpuLight light;
    double power = 0; // luminance-weighted watts (selectionWeight of the emitted colour)
};

// Luminance (Rec. 709) of a linear RGB colour.
float luminance(const glm::vec3& c);
// Weight of a colour in light selection and environment sampling: its luminance, with a floor so
// that a colour outside the luminance weights (pure blue emission, say) still gets a share.
double selectionWeight(const glm::vec3& c);

// Power of a Lambertian emitter of the material's emission over `area`: pi x radiance x area,
// twice that when it emits from both sides.
double lambertianEmitterPower(const Material& material, double area);
// The entry of an emissive primitive (its type, index and the area it is sampled by), or nothing
// when its power is not a positive finite number.
std::optional<LightEntry> areaEmitter(uint32_t type, uint32_t index, float samplingArea, double power);

// An emissive triangle (index: its position in the BVH-ordered array), or nothing for a
// triangle that does not emit or has no area (it cannot be hit). `textureAverage`: its
// emission texture's mean over it (1 without one); black leaves it out.
std::optional<LightEntry> triangleLight(const gpu::GpuTriangle& triangle, uint32_t index, const Material& material,
    glm::vec3 textureAverage = glm::vec3(1.0f));
// An emissive sphere or ellipsoid, or nothing for one that does not emit or is singular.
std::optional<LightEntry> sphereLight(const gpu::GpuSphere& sphere, uint32_t index, const Material& material);
// A point, spot, square or directional light, or nothing for one that emits nothing.
// `sceneRadius` sizes a directional light's power.
std::optional<LightEntry> punctualLight(const PunctualLight& light, float sceneRadius);
// The environment, from its radiance averaged over the sphere (luminance).
LightEntry environmentLight(double averageRadiance, float sceneRadius);

} // namespace pt
