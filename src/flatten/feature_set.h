#pragma once
// Which parts of the megakernel a scene and its switches need. Everything else is removed by
// specialization constants when the pipeline is created (shaders/integrator/features.glsl).
#include "gpu/compute_pipeline.h"
#include "flatten/flat_scene.h"
#include "flatten/integrator_settings.h"

#include <string>
#include <vector>

namespace pt {

struct FeatureSet {
    bool diffuse = true;
    bool mirror = true;
    bool dielectric = true;
    bool conductor = true;
    bool glossy = true;
    bool triangles = true;
    bool spheres = true;
    bool absorption = true;
    bool shadingNormals = true;
    bool emitters = true;
    bool punctualLights = true;
    bool environment = true;
    bool textures = true;      // image textures
    bool normalMaps = true;    // normal or bump maps
    bool alpha = true;         // alpha-tested triangles
    bool procedural = true;    // checkerboard / Perlin textures
    bool unlit = true;         // course replace_all
    bool microfacet = true;    // GGX-rough conductors / dielectrics
    bool pbr = true;           // glTF metallic-roughness
    bool nee = true;
    bool mis = true;
    bool rr = true;
    bool cosineSampling = true;
    uint32_t debugView = 0; // DEBUG_VIEW_*
    bool classic = false;   // the course's classic ray tracer
    bool motion = true;     // moving objects (motion blur)
    bool countRays = false; // per-pixel ray counts for pt bench (Renderer::enableRayCounts)
    uint32_t sampler = 0;   // SAMPLER_*
    uint32_t forcedRandom = 0; // FORCED_RANDOM_*: tests only (random numbers pinned to 0 or 1 - 2^-24)
    bool lightTracing = false; // caustic paths by light tracing, splatted (needs the splat sums)

    // Every feature on: the unspecialised kernel, for comparison and for tests.
    static FeatureSet all(const IntegratorSettings& settings);
    std::vector<SpecializationConstant> constants(uint32_t localSizeX, uint32_t localSizeY) const;
    std::string describe() const; // e.g. "diffuse mirror nee mis rr cosine"
};

FeatureSet computeFeatures(const FlatScene& scene, const IntegratorSettings& settings);

} // namespace pt
