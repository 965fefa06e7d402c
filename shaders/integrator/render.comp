#version 460
// The megakernel: each invocation owns one pixel and adds push.sampleCount samples to its sums.
// Samples are added one at a time, in sample-index order, to running double-float sums
// (integrator/accumulate.glsl) whose whole state is stored, so the result is the same however
// the samples are split over dispatches, tiles, checkpointed runs or merged partitions.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "shared/layout.h"
#include "shared/features.glsl"
#include "integrator/camera.glsl"
#include "integrator/path.glsl"
#include "integrator/debug_view.glsl"
#include "integrator/accumulate.glsl"
#ifdef PT_LIGHT_TRACING
#include "integrator/light_tracer.glsl"
#endif

layout(local_size_x_id = SPEC_LOCAL_SIZE_X, local_size_y_id = SPEC_LOCAL_SIZE_Y) in;

layout(push_constant) uniform PushBlock { GpuRenderPush push; };

void main() {
    uvec2 local = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(local, push.tileSize))) return;
    bindScene(push.sceneParams);
    uvec2 pixel = push.tileOrigin + local;
    if (any(greaterThanEqual(pixel, scene.imageSize))) return;
    uint index = pixel.y * scene.imageSize.x + pixel.x;
    Vec4Ref accumulation = Vec4Ref(scene.accumulation);
    uint base = ACCUMULATION_VEC4S_PER_PIXEL * index;
    vec4 sum = accumulation.v[base + ACCUM_SUM];
    vec3 sumLo = accumulation.v[base + ACCUM_SUM_LO].rgb;
    vec3 sumSquares = accumulation.v[base + ACCUM_SUM_SQUARES].rgb;
    vec3 sumSquaresLo = accumulation.v[base + ACCUM_SUM_SQUARES_LO].rgb;
    for (uint s = 0u; s < push.sampleCount; ++s) {
        Rng rng = rngCreate(pixel, push.sampleStart + s, scene.seed);
        vec2 jitter = rng2(rng, DIM_PIXEL); // box filter: uniform over the pixel
        Ray ray = cameraRay(scene.camera, vec2(pixel) + jitter, scene.imageSize, rng2(rng, DIM_LENS));
        pathTime = HAS_MOTION ? rng1(rng, DIM_TIME) : 0.0; // the shutter is open over [0, 1)
        // Radiance, or a debug view (the NaN mask marks the radiance samples the kernel drops).
        vec3 L;
        if (DEBUG_VIEW == DEBUG_VIEW_NONE || DEBUG_VIEW == DEBUG_VIEW_NAN_MASK) {
            L = tracePath(ray, rng);
            if (DEBUG_VIEW == DEBUG_VIEW_NAN_MASK) L = nanMask(L);
        } else {
            L = debugView(ray);
        }
        // Firefly clamp (viewer option, biased): scale the sample down to a largest component
        // of sampleClamp. NaN fails the comparison and is still dropped below.
        if (push.sampleClamp > 0.0 && maxComponent(L) > push.sampleClamp) L *= push.sampleClamp / maxComponent(L);
        if (allFinite(L)) {
            vec3 sumHi = sum.rgb;
            accumulate(sumHi, sumLo, L);
            sum.rgb = sumHi;
            accumulate(sumSquares, sumSquaresLo, L * L);
        } else {
            sum.w += 1.0; // dropped: counted, contributes zero
        }
        // One light path per pixel and sample, splatted wherever it lands (atomic integer sums).
#ifdef PT_LIGHT_TRACING
        if (lightTracingActive()) traceLightPath(pixel, push.sampleStart + s);
#endif
    }
    accumulation.v[base + ACCUM_SUM] = sum;
    accumulation.v[base + ACCUM_SUM_LO] = vec4(sumLo, 0.0);
    accumulation.v[base + ACCUM_SUM_SQUARES] = vec4(sumSquares, 0.0);
    accumulation.v[base + ACCUM_SUM_SQUARES_LO] = vec4(sumSquaresLo, 0.0);
    if (COUNT_RAYS) {
        UVec4Ref counts = UVec4Ref(push.rayCounts);
        counts.v[index] += uvec4(closestRaysTraced, shadowRaysTraced, 0u, 0u);
    }
}
