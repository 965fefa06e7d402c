// The viewer's diagnostic images (DEBUG_VIEW): what the camera ray finds, instead of
// radiance (or, for the NaN mask, a mark on radiance samples that are not finite). They
// accumulate like radiance, so edges are antialiased by the pixel jitter.
#ifndef PT_INTEGRATOR_DEBUG_VIEW_GLSL
#define PT_INTEGRATOR_DEBUG_VIEW_GLSL
#include "common/math.glsl"
#include "geometry/interaction.glsl"
#include "geometry/traverse.glsl"
#include "shared/features.glsl"
#include "material/material_textures.glsl"
#include "common/rng.glsl"
#include "common/sampling.glsl"
#include "common/ray_offset.glsl"
#include "bsdf/surface_bsdf.glsl"
#include "lights/light_sampling.glsl"
#include "integrator/shadow_ray.glsl"

// BVH cost: node visits of the camera ray's closest-hit query (both trees), shown on a
// blue-green-red ramp from 0 to this many visits (red saturates above it).
const float BVH_COST_FULL_SCALE = 100.0;
// NaN mask: finite samples show as a dim grey of their luminance, so the scene stays legible.
const float NAN_MASK_GREY = 0.25;

vec3 heatRamp(float x) {
    x = clamp(x, 0.0, 1.0);
    return x < 0.5 ? mix(vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0), 2.0 * x)
                   : mix(vec3(0.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0), 2.0 * x - 1.0);
}

float minOf(vec4 v) { return min(min(v.x, v.y), min(v.z, v.w)); }
float maxOf(vec4 v) { return max(max(v.x, v.y), max(v.z, v.w)); }

// Grows [lo, hi] by a wide node's box: the union of its four child boxes (unused slots are empty).
void growByWideNode(GpuBvh4Node n, inout vec3 lo, inout vec3 hi) {
    lo = min(lo, vec3(minOf(n.loX), minOf(n.loY), minOf(n.loZ)));
    hi = max(hi, vec3(maxOf(n.hiX), maxOf(n.hiY), maxOf(n.hiZ)));
}

// Distance from p to the farthest corner of the scene's bounds (the roots of the world, instance
// and sphere trees):
// depth is shown as 1 - t / this, so near surfaces are bright and the far end is black.
float farthestSceneDistance(vec3 p) {
    vec3 lo = vec3(FLOAT_MAX), hi = vec3(-FLOAT_MAX);
    if (HAS_TRIANGLES && scene.numNodes > 0u) growByWideNode(loadTriangleTreeNode(0u), lo, hi);
    if (HAS_INSTANCES && scene.numInstanceNodes > 0u) growByWideNode(loadBvh4Node(scene.instanceNodes, 0u), lo, hi);
    if (HAS_SPHERES && scene.numSphereNodes > 0u) growByWideNode(Bvh4Ref(scene.sphereNodes).v[0], lo, hi);
    return all(lessThanEqual(lo, hi)) ? max(length(max(abs(p - lo), abs(p - hi))), 1e-20) : 1.0;
}

// Red where the radiance sample is NaN or infinite (the samples the kernel drops).
vec3 nanMask(vec3 L) {
    return allFinite(L) ? vec3(NAN_MASK_GREY * clamp(luminance(L), 0.0, 1.0)) : vec3(1.0, 0.0, 0.0);
}

// The share of a surface's scattering in a sharp GGX lobe (alpha below SHARP_LOBE_MAX_ALPHA): a
// rough conductor or dielectric, a PBR metal or transmitter. Light that such a surface reflects
// or transmits onto others is a glossy caustic: a unidirectional path finds it only when its
// BSDF sample from the receiving surface meets the lobe's narrow image of the light, while a
// light subpath carries it there. Smooth (delta) surfaces are the light tracer's instead.
float sharpLobeWeight(GpuMaterial m) {
    if (!(m.alpha >= MIN_ROUGH_ALPHA && m.alpha < SHARP_LOBE_MAX_ALPHA)) return 0.0;
    if (isRoughConductor(m) || isRoughDielectric(m)) return 1.0;
    return isPbr(m) ? max(m.metallic, m.transmission) : 0.0;
}

// The probe's light sample at surface si (vertex `bounce` of the sample's dimensions), of a light
// whose light subpaths start near the scene (not the sky nor a directional light: theirs start on
// a disc around the whole scene, and measured on a room lit by daylight through a door ajar they
// do not pay, bench/RESULTS.md). False where it could not light the surface: a one-sided surface
// seen from behind, a light at infinity, no radiance, a light below an opaque surface. si turns
// to the viewer's side of a double-sided surface.
bool probeLightSample(inout SurfaceInteraction si, GpuMaterial mat, uint bounce, Rng rng, out LightSample ls) {
    bool transmissive = isTransmissiveSurface(mat);
    if (!transmissive && !si.frontFace) {
        if ((mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) == 0u) return false;
        turnToBackSide(si);
    }
    uint index = selectLight(rng1(rng, bounceDimension(bounce, DIM_LIGHT_SELECT)));
    uint type = sceneLights.v[index].type;
    if (type == LIGHT_DIRECTIONAL || type == LIGHT_ENVIRONMENT) return false;
    ls = sampleLightIndex(index, si.p, rng2(rng, bounceDimension(bounce, DIM_LIGHT_POINT)));
    if (ls.pdf <= 0.0 || maxComponent(ls.radiance) <= 0.0) return false;
    return transmissive || dot(ls.wi, si.nSurface) > 0.0;
}

// One cosine-weighted bounce from surface si (not itself sharp, normal n towards the viewer):
// does it meet a surface whose scattering is mostly a sharp lobe and whose light sample finds
// its light? Such bounces carry glossy caustics (sharpLobeWeight).
bool bounceMeetsLitSharpLobe(SurfaceInteraction si, GpuMaterial mat, vec3 n, Rng rng) {
    if (!(HAS_MICROFACET || HAS_PBR) || sharpLobeWeight(mat) >= 0.5) return false;
    Ray bounce;
    bounce.direction =
        toWorld(makeFrame(n), sampleCosineHemisphere(rng2(rng, bounceDimension(1u, DIM_BSDF_DIRECTION))));
    bounce.origin = spawnOrigin(si.p, si.ng, bounce.direction, si.magnitude);
    Hit hit;
    if (!traceClosest(bounce, FLOAT_MAX, hit)) return false;
    SurfaceInteraction sy = makeInteraction(bounce, hit);
    GpuMaterial my = sceneMaterials.v[sy.materialIndex];
    applyTextures(my, sy);
    if (!isSurfaceBsdf(my) || sharpLobeWeight(my) < 0.5) return false;
    LightSample ls;
    return probeLightSample(sy, my, 2u, rng, ls) && !lightOccluded(sy, ls);
}

// Light visibility: at the camera ray's hit on a surface that samples lights, one
// probeLightSample: green 1 where it could light the surface; red counts two outcomes
// (shared/layout.h): 1 where, besides, nothing is in between, plus LIGHT_VIA_SHARP_LOBE where a
// cosine-weighted bounce meets a lit sharp lobe (bounceMeetsLitSharpLobe). The probe
// (src/render/light_visibility_probe.cpp) takes both fractions from the red sums. Blue: the
// distance to that surface, for vertex merging's radius.
vec3 lightVisibility(Ray ray, Rng rng) {
    Hit hit;
    if (scene.numLights == 0u || !traceClosest(ray, FLOAT_MAX, hit)) return vec3(0.0);
    SurfaceInteraction si = makeInteraction(ray, hit);
    GpuMaterial mat = sceneMaterials.v[si.materialIndex];
    applyTextures(mat, si);
    if (!isSurfaceBsdf(mat)) return vec3(0.0);
    LightSample ls;
    if (!probeLightSample(si, mat, 1u, rng, ls)) return vec3(0.0, 0.0, hit.t);
    float visible = lightOccluded(si, ls) ? 0.0 : 1.0;
    vec3 n = dot(si.ns, ray.direction) < 0.0 ? si.ns : -si.ns;
    float viaSharpLobe = bounceMeetsLitSharpLobe(si, mat, n, rng) ? LIGHT_VIA_SHARP_LOBE : 0.0;
    return vec3(visible + viaSharpLobe, 1.0, hit.t);
}

// Albedo, normal, depth and BVH cost: what the camera ray's closest hit shows.
vec3 debugView(Ray ray, Rng rng) {
    if (DEBUG_VIEW == DEBUG_VIEW_LIGHT_VISIBILITY) return lightVisibility(ray, rng);
    Hit hit;
    traversalNodeVisits = 0u;
    bool found = traceClosest(ray, FLOAT_MAX, hit);
    if (DEBUG_VIEW == DEBUG_VIEW_BVH_COST) return heatRamp(float(traversalNodeVisits) / BVH_COST_FULL_SCALE);
    if (!found) return vec3(0.0);
    SurfaceInteraction si = makeInteraction(ray, hit);
    if (DEBUG_VIEW == DEBUG_VIEW_DEPTH) return vec3(clamp(1.0 - hit.t / farthestSceneDistance(ray.origin), 0.0, 1.0));
    // Textures as the integrator sees them: textured colours, normal- or bump-mapped normals.
    GpuMaterial mat = sceneMaterials.v[si.materialIndex];
    applyTextures(mat, si);
    if (DEBUG_VIEW == DEBUG_VIEW_NORMAL) return 0.5 * si.ns + 0.5; // world-space shading normal
    // DEBUG_VIEW_ALBEDO: the material's (textured) base colour; emitters show their emission
    // normalised to a largest component of 1.
    float e = maxComponent(mat.emission);
    return e > 0.0 ? mat.emission / e : mat.baseColor;
}

#endif
