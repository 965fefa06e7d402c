// The CENG795 course's classic ray tracer, its renderer for every scene without
// <Renderer>PathTracing (HW1-HW5 and HW6's BRDF and direct-lighting sets). At each surface:
// ka * Ia, plus direct light shaded with the course's Blinn-Phong, kd cos(theta) +
// ks cos^p(alpha_h) with kd not divided by pi, or with its BRDF when the material names one;
// mirrors, conductors and dielectrics add it too and then follow their reflected or refracted
// ray, up to MaxRecursionDepth. Where the course traced both rays of a dielectric, this follows
// one, chosen with the Fresnel probability, and it samples one light at a time from the light
// table instead of summing over all: the same expectation, so the progressive image converges
// to the course's deterministic one.
#ifndef PT_INTEGRATOR_CLASSIC_GLSL
#define PT_INTEGRATOR_CLASSIC_GLSL
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/ray_offset.glsl"
#include "geometry/interaction.glsl"
#include "lights/light_sampling.glsl"
#include "bsdf/surface_bsdf.glsl"
#include "bsdf/conductor.glsl"
#include "bsdf/dielectric.glsl"
#include "shared/features.glsl"
#include "integrator/background.glsl"
#include "integrator/ray_counts.glsl"
#include "integrator/shadow_ray.glsl"
#include "material/material_textures.glsl"

// Shading of one light's contribution, f cos(theta_i) in the path tracer's terms.
vec3 classicShade(GpuMaterial m, vec3 wo, vec3 wi) {
    if ((m.flags & MATERIAL_FLAG_CLASSIC_PHONG) != 0u) {
        if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
        vec3 h = normalize(wo + wi);
        float lobe = m.classicExponent > 0.0 ? pow(max(h.z, 0.0), m.classicExponent) : 1.0; // pow(0, 0) is undefined
        return m.classicDiffuse * wi.z + m.classicSpecular * lobe;
    }
    // The course's BRDFs: its unnormalised Phong and Blinn-Phong variants use kd without 1/pi
    // (the official images are pi times brighter in their diffuse part than kd / pi gives).
    bool unnormalised = m.type == MATERIAL_GLOSSY && m.glossyModel != GLOSSY_TORRANCE_SPARROW &&
                        (m.flags & MATERIAL_FLAG_NORMALIZED) == 0u;
    if (unnormalised) m.baseColor *= PI;
    return isSurfaceBsdf(m) ? surfaceEval(m, wo, wi) : vec3(0.0);
}

// Up to this many lights are each shaded at every hit, as the course did (point lights then
// cost no noise at all); more are sampled one at a time by power.
const uint CLASSIC_ALL_LIGHTS = 32u;

// Light sample `ls`, shadowed and shaded, weighted by 1 / `pdf`.
vec3 classicLight(SurfaceInteraction si, Frame frame, vec3 woLocal, GpuMaterial mat, LightSample ls, float pdf) {
    if (pdf <= 0.0 || maxComponent(ls.radiance) <= 0.0) return vec3(0.0);
    vec3 fCos = classicShade(mat, woLocal, toLocal(frame, ls.wi));
    if (maxComponent(fCos) <= 0.0) return vec3(0.0);
    if (lightOccluded(si, ls)) return vec3(0.0);
    return fCos * ls.radiance / pdf;
}

vec3 classicDirect(SurfaceInteraction si, Frame frame, vec3 woLocal, GpuMaterial mat, Rng rng, uint depth) {
    vec2 uPoint = rng2(rng, bounceDimension(depth, DIM_LIGHT_POINT));
    if (scene.numLights > CLASSIC_ALL_LIGHTS) {
        LightSample ls = sampleLight(si.p, si.ng, rng1(rng, bounceDimension(depth, DIM_LIGHT_SELECT)), uPoint);
        return classicLight(si, frame, woLocal, mat, ls, ls.pdf);
    }
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < scene.numLights; ++i) {
        // Every light is taken: undo the selection probability the pdf includes.
        float pmf = sceneLights.v[i].pmf;
        if (pmf <= 0.0) continue;
        LightSample ls = sampleLightIndex(i, si.p, uPoint);
        sum += classicLight(si, frame, woLocal, mat, ls, ls.pdf / pmf);
    }
    return sum;
}

// The reflected or refracted ray of a specular surface; invalid for the others.
BsdfSample classicSpecularSample(GpuMaterial m, bool frontFace, Frame frame, vec3 woLocal, float uLobe, vec2 u) {
    bool layeredMirror = HAS_GLOSSY && m.type == MATERIAL_GLOSSY && maxComponent(m.mirror) > 0.0;
    if ((HAS_MIRROR && m.type == MATERIAL_MIRROR && m.alpha == 0.0) || layeredMirror) {
        // The course's mirror: reflectance km at every angle, no Fresnel.
        BsdfSample s = invalidBsdfSample();
        if (woLocal.z <= 0.0) return s;
        s.wi = toWorld(frame, vec3(-woLocal.xy, woLocal.z));
        s.weight = layeredMirror ? m.mirror : m.baseColor;
        s.pdf = 1.0;
        s.isDelta = true;
        s.valid = true;
        return s;
    }
    if (m.alpha == 0.0) {
        if (HAS_DIELECTRIC && m.type == MATERIAL_DIELECTRIC)
            return dielectricSample(m.baseColor, m.ior, frontFace, frame, woLocal, uLobe);
        if (HAS_CONDUCTOR && m.type == MATERIAL_CONDUCTOR)
            return conductorSample(m.baseColor, m.conductorEta, m.conductorK, frame, woLocal);
    } else if (m.type == MATERIAL_DIELECTRIC || m.type == MATERIAL_CONDUCTOR || m.type == MATERIAL_MIRROR) {
        // The course's Roughness, rendered as GGX (see ceng795_materials.cpp); a glTF metal.
        if (isSurfaceBsdf(m)) return surfaceSample(m, frame, woLocal, uLobe, u);
    }
    return invalidBsdfSample();
}

vec3 traceClassic(Ray ray, Rng rng) {
    vec3 L = vec3(0.0);
    vec3 beta = vec3(1.0);
    for (uint depth = 1u;; ++depth) {
        Hit hit;
        countClosestRay();
        if (!traceClosest(ray, FLOAT_MAX, hit)) {
            L += beta * (HAS_ENVIRONMENT && scene.envWidth > 0u ? envRadiance(ray.direction)
                                                                : backgroundRadiance(ray.direction, depth == 1u));
            break;
        }
        SurfaceInteraction si = makeInteraction(ray, hit);
        GpuMaterial mat = sceneMaterials.v[si.materialIndex];
        applyTextures(mat, si);
        if (HAS_ABSORPTION && mat.type == MATERIAL_DIELECTRIC && !si.frontFace &&
            (mat.flags & MATERIAL_FLAG_ABSORBING) != 0u)
            beta *= exp(-mat.sigmaA * hit.t);
        // Object lights seen directly or through mirrors and glass.
        if (HAS_EMITTERS) L += beta * emittedRadiance(mat, si.frontFace);
        if (HAS_UNLIT && (mat.flags & MATERIAL_FLAG_UNLIT) != 0u) {
            L += beta * mat.baseColor; // replace_all: the texel, unshaded
            break;
        }
        vec3 wo = -ray.direction;
        // Shaded from whichever side the ray arrived, as the course's tracer did.
        Frame frame = makeFrame(dot(si.ns, wo) < 0.0 ? -si.ns : si.ns);
        orientMaterialFrame(frame, mat);
        if (dot(si.ng, wo) < 0.0) si.ng = -si.ng;
        vec3 woLocal = toLocal(frame, wo);
        L += beta * mat.ambient * scene.ambientLight;
        if (USE_NEE && scene.numLights > 0u) L += beta * classicDirect(si, frame, woLocal, mat, rng, depth);
        if (depth >= scene.maxDepth) break;
        BsdfSample bs = classicSpecularSample(mat, si.frontFace, frame, woLocal,
            rng1(rng, bounceDimension(depth, DIM_BSDF_LOBE)), rng2(rng, bounceDimension(depth, DIM_BSDF_DIRECTION)));
        if (!bs.valid || maxComponent(bs.weight) <= 0.0) break;
        beta *= bs.weight;
        ray.origin = spawnOrigin(si.p, si.ng, bs.wi, si.magnitude);
        ray.direction = bs.wi;
    }
    return L;
}

#endif
