#pragma once
// The light-selection table: every emitter (emissive triangles and spheres, punctual lights, the
// environment) in one list, chosen with probability proportional to its emitted power through a
// CDF the kernel binary-searches. Each light type's entry and power: lights/light_entry.h.
#include "lights/light_entry.h" // luminance, selectionWeight
#include "lights/light_tree.h"
#include "scene/scene.h"
#include "shared/layout.h"

#include <functional>
#include <span>
#include <vector>

namespace pt {

struct LightTable {
    std::vector<gpu::GpuLight> lights;
    std::vector<float> cdf; // lights.size() + 1 entries, cdf[0] = 0, cdf.back() = 1
    double totalPower = 0;  // sum of the power estimates (luminance-weighted watts)
    uint32_t environmentIndex = NO_LIGHT;
    std::vector<double> power; // each light's weight (luminance-weighted watts)
    // The tree over the bounded lights (empty: selection by the CDF alone), built by flattenScene
    // once the geometry is final (lights/light_tree.h).
    LightTree tree;
};

// Builds the table over the final (BVH-ordered) `triangles` and `spheres`, storing each
// emitter's index in its primitive's lightIndex (NO_LIGHT for the rest). Zero-area emitters
// are left out: they cannot be hit. `sceneRadius` sizes a directional light's power.
// `environmentRadiance` >= 0 adds the environment (its average luminance sizes its power);
// its entry is then the last one.
// `triangleEmission(i)`, when given, is triangle i's emission texture averaged over it (RGB; 1
// without a texture; lights/texture_emission.h): its power is weighed by it, and a triangle whose
// average is black leaves the table.
LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<gpu::GpuSphere> spheres,
    std::span<const PunctualLight> punctual, std::span<const Material> materials, float sceneRadius,
    double environmentRadiance = -1.0, const std::function<glm::vec3(uint32_t)>& triangleEmission = {});

// Whether some receiver sees a triangle emitter under at least SPHERICAL_SAMPLING_MIN (light
// sampling picks directions in its solid angle there; shaders/lights/triangle_light.glsl): the
// centroids of up to `maxReceivers` of the non-emitting triangles among the first `worldTriangles`
// (world space; evenly strided) against every emitting one. Where none does, solid-angle sampling
// would never be chosen and its code is left out of the kernel.
bool someReceiverSeesALargeTriangleLight(
    std::span<const gpu::GpuTriangle> triangles, size_t worldTriangles, size_t maxReceivers = 4096);

// The probability that the power CDF selects a bounded light (one before the lights at infinity):
// the light tree's share when it selects among them.
float boundedLightShare(const LightTable& table);

// Triangles only.
LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<const Material> materials);

} // namespace pt
