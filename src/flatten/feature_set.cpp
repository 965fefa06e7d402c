#include "flatten/feature_set.h"

#include "shared/layout.h"

#include <sstream>

namespace pt {

std::string IntegratorSettings::describe() const {
    std::ostringstream s;
    if (classic) s << "integrator=classic ";
    s << "nee=" << (nee ? "on" : "off") << " mis=" << (mis ? "on" : "off") << " rr=" << (rr ? "on" : "off")
      << " sampling=" << (sampling == DirectionSampling::Cosine ? "cosine" : "uniform")
      << " sampler=" << (sampler == SamplerKind::Sobol ? "sobol" : "independent") << " max-depth=" << maxDepth
      << " rr-start=" << rrStartDepth << " rr-threshold=" << rrThreshold
      << " light-tracing=" << (lightTracing ? "on" : "off") << " seed=" << seed;
    return s.str();
}

FeatureSet FeatureSet::all(const IntegratorSettings& settings) {
    FeatureSet f;
    f.nee = settings.nee;
    f.mis = settings.nee && settings.mis;
    f.rr = settings.rr;
    f.cosineSampling = settings.sampling == DirectionSampling::Cosine;
    f.classic = settings.classic;
    f.sampler = settings.sampler == SamplerKind::Sobol ? SAMPLER_SOBOL : SAMPLER_INDEPENDENT;
    f.lightTracing = false; // an estimator the scene decides (computeFeatures), not a compiled-in feature
    return f;
}

FeatureSet computeFeatures(const FlatScene& scene, const IntegratorSettings& settings) {
    FeatureSet f;
    f.diffuse = f.mirror = f.dielectric = f.conductor = f.glossy = f.absorption = f.shadingNormals = f.emitters = false;
    f.textures = f.normalMaps = f.alpha = f.procedural = f.unlit = f.microfacet = f.pbr = false;
    auto usesTexture = [&](uint32_t slot) {
        if (slot == NO_TEXTURE) return;
        const uint32_t type = scene.textures[slot].type;
        f.textures |= type == TEXTURE_IMAGE;
        f.procedural |= type != TEXTURE_IMAGE;
    };
    for (const auto& m : scene.materials) {
        for (uint32_t slot : {m.baseColorTexture, m.specularTexture, m.metallicRoughnessTexture, m.normalTexture, m.emissiveTexture})
            usesTexture(slot);
        f.normalMaps |= m.normalTexture != NO_TEXTURE;
        f.unlit |= (m.flags & MATERIAL_FLAG_UNLIT) != 0u;
        f.pbr |= m.type == MATERIAL_PBR;
        f.microfacet |= (m.type == MATERIAL_CONDUCTOR || m.type == MATERIAL_DIELECTRIC) && m.alpha > 0.0f;
        f.emitters |= m.emissiveTexture != NO_TEXTURE || (m.flags & MATERIAL_FLAG_UNLIT) != 0u;
        f.diffuse |= m.type == MATERIAL_DIFFUSE;
        f.mirror |= m.type == MATERIAL_MIRROR;
        f.dielectric |= m.type == MATERIAL_DIELECTRIC;
        f.conductor |= m.type == MATERIAL_CONDUCTOR;
        f.glossy |= m.type == MATERIAL_GLOSSY;
        f.absorption |= (m.flags & MATERIAL_FLAG_ABSORBING) != 0u; // dielectrics and PBR volumes
        f.emitters |= m.emission.x > 0 || m.emission.y > 0 || m.emission.z > 0;
    }
    usesTexture(scene.backgroundTexture);
    for (const auto& t : scene.triangles) {
        f.shadingNormals |= (t.flags & TRIANGLE_FLAG_SHADING_NORMALS) != 0u;
        f.alpha |= (t.flags & TRIANGLE_FLAG_ALPHA_TESTED) != 0u;
    }
    f.triangles = !scene.triangles.empty();
    f.spheres = !scene.spheres.empty();
    f.punctualLights = false;
    for (const auto& l : scene.lights.lights)
        f.punctualLights |= l.type == LIGHT_POINT || l.type == LIGHT_DIRECTIONAL || l.type == LIGHT_SPOT || l.type == LIGHT_SQUARE;
    f.environment = scene.environment.width > 0;
    // Light sampling needs something to sample and a non-delta surface that can use it.
    // (The environment is in the table too.)
    f.nee = settings.nee && !scene.lights.lights.empty() && (f.diffuse || f.glossy || f.pbr || f.microfacet);
    f.mis = f.nee && settings.mis;
    f.rr = settings.rr;
    f.cosineSampling = settings.sampling == DirectionSampling::Cosine;
    // The classic ray tracer always samples lights (on every surface: its Blinn-Phong terms
    // apply to mirrors and glass too), never continues diffuse paths, so no MIS or roulette.
    f.motion = !scene.motions.empty();
    f.classic = settings.classic;
    f.sampler = settings.sampler == SamplerKind::Sobol ? SAMPLER_SOBOL : SAMPLER_INDEPENDENT;
    if (f.classic) {
        f.nee = !scene.lights.lights.empty();
        f.mis = f.rr = false;
    }
    // Light tracing pays only where caustics can be seen directly: a specular surface, a
    // receiver and an area emitter. Left to the path tracer: absorbing interiors, cut-outs
    // and moving objects (the light path does not model them).
    bool areaEmitters = false;
    for (const auto& l : scene.lights.lights) areaEmitters |= l.type == LIGHT_TRIANGLE || l.type == LIGHT_SPHERE;
    f.lightTracing = settings.lightTracing && !f.classic && areaEmitters && (f.mirror || f.dielectric || f.conductor) &&
                     (f.diffuse || f.glossy || f.microfacet) && !f.absorption && !f.alpha && !f.motion;
    return f;
}

std::vector<SpecializationConstant> FeatureSet::constants(uint32_t localSizeX, uint32_t localSizeY) const {
    return {
        {SPEC_LOCAL_SIZE_X, localSizeX},
        {SPEC_LOCAL_SIZE_Y, localSizeY},
        {SPEC_HAS_DIFFUSE, diffuse},
        {SPEC_HAS_MIRROR, mirror},
        {SPEC_HAS_DIELECTRIC, dielectric},
        {SPEC_HAS_ABSORPTION, absorption},
        {SPEC_HAS_SHADING_NORMALS, shadingNormals},
        {SPEC_HAS_EMITTERS, emitters},
        {SPEC_USE_NEE, nee},
        {SPEC_USE_MIS, mis},
        {SPEC_USE_RR, rr},
        {SPEC_COSINE_SAMPLING, cosineSampling},
        {SPEC_HAS_SPHERES, spheres},
        {SPEC_HAS_TRIANGLES, triangles},
        {SPEC_HAS_CONDUCTOR, conductor},
        {SPEC_HAS_PUNCTUAL_LIGHTS, punctualLights},
        {SPEC_HAS_GLOSSY, glossy},
        {SPEC_HAS_ENVIRONMENT, environment},
        {SPEC_HAS_TEXTURES, textures},
        {SPEC_HAS_NORMAL_MAPS, normalMaps},
        {SPEC_HAS_ALPHA, alpha},
        {SPEC_HAS_PROCEDURAL, procedural},
        {SPEC_HAS_UNLIT, unlit},
        {SPEC_HAS_MICROFACET, microfacet},
        {SPEC_HAS_PBR, pbr},
        {SPEC_DEBUG_VIEW, debugView},
        {SPEC_CLASSIC, classic},
        {SPEC_HAS_MOTION, motion},
        {SPEC_COUNT_RAYS, countRays},
        {SPEC_SAMPLER, sampler},
        {SPEC_FORCED_RANDOM, forcedRandom},
        {SPEC_LIGHT_TRACING, lightTracing},
    };
}

std::string FeatureSet::describe() const {
    std::string s;
    auto add = [&](bool on, const char* name) {
        if (!on) return;
        if (!s.empty()) s += ' ';
        s += name;
    };
    add(classic, "classic");
    add(triangles, "triangles");
    add(spheres, "spheres");
    add(diffuse, "diffuse");
    add(mirror, "mirror");
    add(dielectric, "dielectric");
    add(conductor, "conductor");
    add(glossy, "glossy");
    add(pbr, "pbr");
    add(microfacet, "microfacet");
    add(absorption, "absorption");
    add(shadingNormals, "shading-normals");
    add(emitters, "emitters");
    add(punctualLights, "punctual-lights");
    add(environment, "environment");
    add(textures, "textures");
    add(procedural, "procedural-textures");
    add(normalMaps, "normal-maps");
    add(alpha, "alpha");
    add(unlit, "unlit");
    add(motion, "motion-blur");
    add(nee, "nee");
    add(mis, "mis");
    add(rr, "rr");
    add(lightTracing, "light-tracing");
    s += cosineSampling ? " cosine-sampling" : " uniform-sampling";
    if (sampler == SAMPLER_SOBOL) s += " sobol";
    if (countRays) s += " ray-counts";
    if (forcedRandom != FORCED_RANDOM_OFF) s += forcedRandom == FORCED_RANDOM_ZERO ? " forced-random-0" : " forced-random-1";
    return s;
}

} // namespace pt
