#pragma once
// The light-selection table: every emissive triangle, chosen with probability proportional to
// its emitted power (radiance luminance x area), through a CDF the kernel binary-searches.
#include "scene/scene.h"
#include "shared/layout.h"

#include <span>
#include <vector>

namespace pt {

struct LightTable {
    std::vector<gpu::GpuLight> lights;
    std::vector<float> cdf; // lights.size() + 1 entries, cdf[0] = 0, cdf.back() = 1
    double totalPower = 0;  // sum of luminance(radiance) x area (x2 when double-sided), in W/sr-ish units
};

// Builds the table over `triangles` (final, BVH-ordered) and stores each emitter's index in its
// triangle's lightIndex (NO_LIGHT for the rest). Zero-area emitters are left out: they cannot be hit.
LightTable buildLightTable(std::span<gpu::GpuTriangle> triangles, std::span<const Material> materials);

} // namespace pt
