// The samples of one pixel: their camera rays, and the loop that traces them and adds them to
// the pixel's sums in sample order.
#ifndef PT_INTEGRATOR_PIXEL_SAMPLES_GLSL
#define PT_INTEGRATOR_PIXEL_SAMPLES_GLSL
#include "shared/features.glsl"
#include "common/rng.glsl"
#include "geometry/motion.glsl"
#include "integrator/camera.glsl"
#include "integrator/path.glsl"
#include "integrator/debug_view.glsl"
#include "integrator/accumulate.glsl"
#ifdef PT_BDPT
#include "integrator/bdpt.glsl"
#endif

// The camera ray of sample `rng` of `pixel`; sets the path's shutter time.
Ray sampleCameraRay(uvec2 pixel, Rng rng) {
    vec2 jitter = rng2(rng, DIM_PIXEL); // box filter: uniform over the pixel
    Ray ray = cameraRay(scene.camera, vec2(pixel) + jitter, scene.imageSize, rng2(rng, DIM_LENS));
    pathTime = HAS_MOTION ? rng1(rng, DIM_TIME) : 0.0; // the shutter is open over [0, 1)
    return ray;
}

// What one sample adds: the NaN-mask view's mask, or the radiance under the firefly clamp
// (viewer option, biased: scaled down to a largest component of `sampleClamp` where that is
// positive; NaN fails the comparison and is dropped by addToPixelSums).
vec3 sampleValue(vec3 L, float sampleClamp) {
    if (DEBUG_VIEW == DEBUG_VIEW_NAN_MASK) L = nanMask(L);
    if (sampleClamp > 0.0 && maxComponent(L) > sampleClamp) L *= sampleClamp / maxComponent(L);
    return L;
}

// Samples `first` to `first + count - 1` of `pixel`, one at a time, added to `sums` in order; their
// random numbers keyed by `streamKey` (integrator/pixel_groups.glsl, cameraStreamKey).
void addSamplesOneByOne(uvec2 pixel, uvec2 streamKey, uint first, uint count, float sampleClamp, inout PixelSums sums) {
    bool radiance = DEBUG_VIEW == DEBUG_VIEW_NONE || DEBUG_VIEW == DEBUG_VIEW_NAN_MASK;
    for (uint s = 0u; s < count; ++s) {
        Rng rng = rngCreate(streamKey, first + s, scene.seed);
        Ray ray = sampleCameraRay(pixel, rng);
        addToPixelSums(sums, sampleValue(radiance ? tracePath(ray, rng) : debugView(ray, rng), sampleClamp));
    }
}

// The same by path tracing with path regeneration (Novak et al. 2010): an invocation whose path
// has ended starts its next sample at once instead of idling until the longest path of its SIMD
// group ends. Lavapipe runs 8 invocations as one vector and a loop costs as much as its slowest
// lane, so with Russian roulette one path at a time paid the longest of 8 paths for every
// sample (bench/RESULTS.md, "Path regeneration"). Each pixel still adds its own samples in
// sample order: the sums are bit-identical to addSamplesOneByOne's.
void addPathSamplesRegenerated(
    uvec2 pixel, uvec2 streamKey, uint first, uint count, float sampleClamp, inout PixelSums sums) {
    if (count == 0u) return;
    uint s = 0u;
    bool start = true;
    PathState st;
    while (true) {
        if (start) {
            Rng rng = rngCreate(streamKey, first + s, scene.seed);
            st = pathStart(sampleCameraRay(pixel, rng), rng);
        }
        start = !pathStep(st);
        if (!start) continue;
        addToPixelSums(sums, sampleValue(st.L, sampleClamp));
        if (++s >= count) break;
    }
}

#ifdef PT_BDPT
// The same by bidirectional path tracing: each sample's light subpath first (its connections
// to the camera are splatted), then its camera path, connected to the light subpath's vertices.
// With vertex merging's camera phase (integrator/vcm.glsl) the light subpath is the one the light
// phase stored.
bool bdptCameraConnects() { return scene.camera.lensRadius == 0.0; } // a thin lens would need the lens sampled

void addBdptSamples(uvec2 pixel, uint first, uint count, float sampleClamp, inout PixelSums sums) {
    bool cameraConnects = bdptCameraConnects();
    for (uint s = 0u; s < count; ++s) {
        Rng rng = rngCreate(pixel, first + s, scene.seed);
        Ray ray = sampleCameraRay(pixel, rng);
        if (mergingPhase(VCM_PHASE_CAMERA))
            lightVertexCount = vcmVertexCount(bdptPixelIndex);
        else
            traceLightSubpath(rng, cameraConnects);
        addToPixelSums(sums, sampleValue(traceBdptCameraPath(ray, rng, cameraConnects), sampleClamp));
    }
}

// Vertex merging's light phase: this pixel's light subpath of sample `index`, its camera
// connections splatted and its vertices stored for the camera phase.
void storeBdptLightSubpath(uvec2 pixel, uint index) {
    traceLightSubpath(rngCreate(pixel, index, scene.seed), bdptCameraConnects());
    storeVcmVertexCount(bdptPixelIndex, lightVertexCount);
}

// Vertex merging's pilot: a light subpath of a sequence of its own, its vertices counted per
// pilot cell (integrator/vcm.glsl, mergeKeep), nothing splatted.
void countPilotLightSubpath(uvec2 pixel) { traceLightSubpath(rngCreate(pixel, 0u, scene.seed ^ 0x5bd1e995u), false); }
#endif

// Samples `first` to `first + count - 1` of `pixel`, added to `sums` in that order. (If-else on
// one constant at a time: the specializer then deletes the branches not taken, and with them
// the second copy of the path tracer that the driver would otherwise compile.)
void addPixelSamples(uvec2 pixel, uvec2 streamKey, uint first, uint count, float sampleClamp, inout PixelSums sums) {
    if (CLASSIC) addSamplesOneByOne(pixel, streamKey, first, count, sampleClamp, sums);
#ifdef PT_BDPT
    else if (BDPT && (DEBUG_VIEW == DEBUG_VIEW_NONE || DEBUG_VIEW == DEBUG_VIEW_NAN_MASK))
        addBdptSamples(pixel, first, count, sampleClamp, sums);
#endif
    // Shared samples keep a SIMD vector's paths in step: regenerating them would part them.
    else if (!SHARED_SAMPLES && (DEBUG_VIEW == DEBUG_VIEW_NONE || DEBUG_VIEW == DEBUG_VIEW_NAN_MASK))
        addPathSamplesRegenerated(pixel, streamKey, first, count, sampleClamp, sums);
    else
        addSamplesOneByOne(pixel, streamKey, first, count, sampleClamp, sums);
}

#endif
