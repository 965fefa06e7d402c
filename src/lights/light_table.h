#pragma once
// The light-selection table: every emitter (emissive triangles and spheres, point and
// directional lights) in one list, chosen with probability proportional to its emitted power
// through a CDF the kernel binary-searches.
#include "scene/scene.h"
#include "shared/layout.h"

#include <span>
#include <vector>

namespace pt {

struct LightTable {
    std::vector<gpu::GpuLight> lights;
    std::vector<float> cdf; // lights.size() + 1 entries, cdf[0] = 0, cdf.back() = 1
    double totalPower = 0;  // sum of the power estimates (luminance-weighted watts)
    uint32_t environmentIndex = NO_LIGHT;
};

// Builds the table over the final (BVH-ordered) `triangles` and `spheres`, storing each
// emitter's index in its primitive's lightIndex (NO_LIGHT for the rest). Zero-area emitters
// are left out: they cannot be hit. `sceneRadius` sizes a directional light's power.
// `environmentRadiance` >= 0 adds the environment (its average luminance sizes its power);
// its entry is then the last one.
LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<gpu::GpuSphere> spheres,
    std::span<const PunctualLight> punctual, std::span<const Material> materials, float sceneRadius,
    double environmentRadiance = -1.0);

// Luminance (Rec. 709) of a linear RGB colour.
float luminance(const glm::vec3& c);
// Weight of a colour in light selection and environment sampling: its luminance, with a floor so
// that a colour outside the luminance weights (pure blue emission, say) still gets a share.
double selectionWeight(const glm::vec3& c);

// Triangles only.
LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<const Material> materials);

} // namespace pt
