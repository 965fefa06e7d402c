// Light tracing of caustics (see integrator/caustic_partition.glsl for which paths, and why): a
// path starts on an area light, must meet a specular surface first, follows delta bounces and
// BSDF samples at receivers, and at every receiver is connected to the pinhole camera and added
// to the pixel it projects to. One light path per pixel and sample: N = spp x pixels in all.
//
// Light paths carry importance, not radiance, so two things differ from the path tracer
// (Veach 1997, ch. 5): refraction does not scale by 1/eta^2, and shading normals get the
// adjoint correction |wL.ns| |wC.ng| / (|wL.ng| |wC.ns|) at each vertex (wL towards the light,
// wC towards the camera).
#ifndef PT_INTEGRATOR_LIGHT_TRACER_GLSL
#define PT_INTEGRATOR_LIGHT_TRACER_GLSL
#extension GL_EXT_shader_atomic_int64 : require
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/sampling.glsl"
#include "common/ray_offset.glsl"
#include "geometry/interaction.glsl"
#include "geometry/sphere.glsl"
#include "lights/light_common.glsl"
#include "lights/sphere_light.glsl"
#include "lights/triangle_light.glsl"
#include "bsdf/surface_bsdf.glsl"
#include "bsdf/mirror.glsl"
#include "bsdf/conductor.glsl"
#include "bsdf/dielectric.glsl"
#include "textures/texture.glsl"
#include "material/material_textures.glsl"
#include "integrator/caustic_partition.glsl"
#include "integrator/shadow_ray.glsl"
#include "integrator/ray_counts.glsl"
#include "integrator/splat.glsl"
#include "lights/emitter_sampling.glsl"

// An opaque surface as seen from the side `front` says (the camera's, or the light path's own),
// with the light arriving from wLight: false where the path tracer would find nothing (a
// one-sided surface from behind, or wLight below the surface's own normal); otherwise si is
// turned to that side and `frame` is its shading frame there, as the path tracer builds it.
bool opaqueFrame(inout SurfaceInteraction si, GpuMaterial mat, bool front, vec3 wLight, out Frame frame) {
    if (!front && (mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) == 0u) return false;
    if (!front) turnToBackSide(si);
    if (HAS_NORMAL_MAPS && dot(wLight, si.nSurface) <= 0.0) return false;
    frame = makeFrame(front ? si.ns : -si.ns);
    return true;
}

// Connects a light path arriving at receiver si (from direction wLight) to the camera and
// splats it. beta: the path's weight (emitted radiance over the density of the path so far).
void connectToCamera(SurfaceInteraction si, GpuMaterial mat, vec3 wLight, vec3 beta) {
    CameraView view;
    if (!viewFromPinhole(scene.camera, scene.imageSize, si.p, view)) return;
    // The receiver as the camera ray would find it.
    Frame frame;
    if (!opaqueFrame(si, mat, dot(view.wCamera, si.ng) > 0.0, wLight, frame)) return;
    vec3 fCos = surfaceEval(mat, toLocal(frame, view.wCamera), toLocal(frame, wLight)); // f |wL.ns|
    float cosLightGeometric = abs(dot(wLight, si.ng));
    if (maxComponent(fCos) <= 0.0 || cosLightGeometric < 1e-7) return;
    if (cameraOccluded(si, view)) return;
    // Per unit area of the receiver, with the adjoint's shading-normal correction |wC.ng| / |wL.ng|.
    splatAdd(view.pixel, beta * fCos * (view.importance * abs(dot(view.wCamera, si.ng)) / cosLightGeometric));
}

// One light path in flight (see traceLightPaths for why it advances a segment at a time).
struct LightPathState {
    Ray ray;         // the segment to trace next
    Rng rng;         // the path's random numbers
    vec3 beta;       // the path's weight: emitted radiance over the density of the path so far
    vec3 throughput; // product of the bounce weights, for Russian roulette
    uint segments;   // segments of the light path so far, this one included
};

// Starts light path number `sampleIndex` of `pixel` (the pixel only names the path; it lands
// wherever it lands) on an emitter. False when there is nothing to trace.
bool lightPathStart(uvec2 pixel, uint sampleIndex, out LightPathState lp) {
    lp.rng = rngCreate(pixel, sampleIndex, scene.seed);
    if (scene.numLights == 0u || scene.maxDepth < 3u) return false; // camera, one bounce, light: 3 segments
    uint lightIndex = selectLight(rng1(lp.rng, lightPathDimension(DIM_LT_SELECT)));
    EmitterPoint e = sampleEmitterPoint(lightIndex, rng2(lp.rng, lightPathDimension(DIM_LT_POINT)));
    if (!e.valid) return false;
    // Cosine-weighted emission from the front side (or either side of a double-sided emitter):
    // beta = Le cos / (pdf_area pdf_direction) = Le pi / pdf_area.
    vec3 n = e.ng;
    float sides = 1.0;
    if ((sceneMaterials.v[e.materialIndex].flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u) {
        sides = 2.0;
        if (rng1(lp.rng, lightPathDimension(DIM_LT_SIDE)) < 0.5) n = -n;
    }
    vec3 local = sampleCosineHemisphere(rng2(lp.rng, lightPathDimension(DIM_LT_EMIT)));
    if (local.z <= 0.0) return false;
    lp.beta = e.Le * (PI * sides / e.pdf);
    lp.throughput = vec3(1.0);
    lp.ray.origin = offsetRayOrigin(e.p, n, e.magnitude);
    lp.ray.direction = toWorld(makeFrame(n), local);
    lp.segments = 1u;
    return true;
}

// Traces lp.ray, splats the connection to the camera where it lands on a receiver, and sets up
// the next segment. False when the path has ended.
bool lightPathStep(inout LightPathState lp) {
    Hit hit;
    countClosestRay();
    if (!traceClosest(lp.ray, FLOAT_MAX, hit)) return false;
    SurfaceInteraction si = makeInteraction(lp.ray, hit);
    GpuMaterial mat = sceneMaterials.v[si.materialIndex];
    applyTextures(mat, si);
    vec3 wLight = -lp.ray.direction;
    uint segments = lp.segments;
    uint bounce = segments - 1u; // vertices behind this one
    bool receiver = isCausticReceiver(mat);
    // Light reaching a receiver straight from the emitter is the path tracer's (direct
    // light); so is everything from a material the light path does not follow.
    if ((receiver && bounce == 0u) || (!receiver && !isSpecularChainMaterial(mat))) return false;
    if (receiver && segments + 1u <= scene.maxDepth) connectToCamera(si, mat, wLight, lp.beta);
    // Another bounce needs one more segment before the camera's.
    if (segments + 2u > scene.maxDepth) return false;

    vec3 weight;
    vec3 wCamera;
    if (receiver) {
        // Onwards from a receiver by BSDF sampling, with the adjoint BSDF f(wC, wL).
        Frame frame;
        if (!opaqueFrame(si, mat, si.frontFace, wLight, frame)) return false;
        vec3 wLightLocal = toLocal(frame, wLight);
        BsdfSample bs = surfaceSample(mat, frame, wLightLocal, rng1(lp.rng, lightBounceDimension(bounce, DIM_LT_LOBE)),
            rng2(lp.rng, lightBounceDimension(bounce, DIM_LT_DIRECTION)));
        if (!bs.valid || bs.isDelta || !(bs.pdf > 0.0)) return false;
        wCamera = bs.wi;
        if (!isReversibleOpaqueBounce(si.ng, wLight, wCamera)) return false;
        float cosLightGeometric = abs(dot(wLight, si.ng));
        if (cosLightGeometric < 1e-7) return false;
        weight = surfaceEval(mat, toLocal(frame, wCamera), wLightLocal) *
                 (abs(dot(wCamera, si.ng)) / (cosLightGeometric * bs.pdf));
    } else {
        BsdfSample bs;
        if (HAS_DIELECTRIC && mat.type == MATERIAL_DIELECTRIC) {
            Frame frame = makeFrame(dot(si.ns, wLight) < 0.0 ? -si.ns : si.ns);
            bs = dielectricSample(mat.baseColor, mat.ior, si.frontFace, frame, toLocal(frame, wLight),
                rng1(lp.rng, lightBounceDimension(bounce, DIM_LT_LOBE)));
            bs.weight *= bs.etaScale; // importance is not compressed by refraction
        } else {
            Frame frame;
            if (!opaqueFrame(si, mat, si.frontFace, wLight, frame)) return false;
            vec3 woLocal = toLocal(frame, wLight);
            if (HAS_MIRROR && mat.type == MATERIAL_MIRROR)
                bs = mirrorSample(mat.baseColor, frame, woLocal);
            else
                bs = conductorSample(mat.baseColor, mat.conductorEta, mat.conductorK, frame, woLocal);
        }
        if (!bs.valid) return false;
        wCamera = bs.wi;
        if (!isReversibleDeltaBounce(si.ng, si.ns, wLight, wCamera)) return false;
        float denominator = abs(dot(wLight, si.ng)) * abs(dot(wCamera, si.ns));
        if (denominator < 1e-7) return false;
        weight = bs.weight * (abs(dot(wLight, si.ns)) * abs(dot(wCamera, si.ng)) / denominator);
    }
    if (!allFinite(weight) || maxComponent(weight) <= 0.0) return false;
    lp.beta *= weight;
    lp.throughput *= weight;

    if (USE_RR && segments + 1u >= scene.rrStartDepth) {
        float m = maxComponent(lp.throughput) / scene.rrThreshold;
        if (m < 1.0) {
            if (rng1(lp.rng, lightBounceDimension(bounce, DIM_LT_ROULETTE)) >= m) return false;
            lp.beta /= m;
            lp.throughput /= m;
        }
    }
    lp.ray.origin = spawnOrigin(si.p, si.ng, wCamera, si.magnitude);
    lp.ray.direction = wCamera;
    lp.segments = segments + 1u;
    return true;
}

// Light paths `first` to `first + count - 1` of `pixel`, each splatted wherever it lands. Most
// end at their first hit (on a receiver: direct light, the path tracer's), a few go on through
// glass and mirrors; an invocation whose path ended starts its next at once (path regeneration,
// as integrator/pixel_samples.glsl does for camera paths) instead of waiting for the longest of
// its SIMD group. The splats are integer sums, so the order they land in changes nothing.
void traceLightPaths(uvec2 pixel, uint first, uint count) {
    uint s = 0u;
    bool start = true;
    LightPathState lp;
    while (s < count) {
        if (start) {
            start = false;
            if (!lightPathStart(pixel, first + s, lp)) {
                start = true;
                ++s;
                continue;
            }
        }
        if (!lightPathStep(lp)) {
            start = true;
            ++s;
        }
    }
}

#endif
