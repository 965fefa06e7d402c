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
#include "integrator/pixel_samples.glsl"
#include "integrator/pixel_groups.glsl"
#include "integrator/ray_counts.glsl"
#ifdef PT_LIGHT_TRACING
#include "integrator/light_tracer.glsl"
#endif

layout(local_size_x_id = SPEC_LOCAL_SIZE_X, local_size_y_id = SPEC_LOCAL_SIZE_Y) in;

layout(push_constant) uniform PushBlock { GpuRenderPush push; };

void main() {
    uvec2 local = invocationPixel(push.blockStride);
    if (any(greaterThanEqual(local, push.tileSize))) return;
    bindScene(push.sceneParams);
    uvec2 pixel = push.tileOrigin + local;
    if (any(greaterThanEqual(pixel, scene.imageSize))) return;
    if (push.sampleCount == 0u) return;
    uint index = pixel.y * scene.imageSize.x + pixel.x;
    Vec4Ref accumulation = Vec4Ref(scene.accumulation);
    uint base = ACCUMULATION_VEC4S_PER_PIXEL * index;
    uint first = push.sampleStart, count = push.sampleCount;
    uvec4 adaptiveSamples;
    if (push.adaptiveSamples != 0ul) {
        // This pixel's share of the epoch's rounds (GpuRenderPush::adaptiveSamples).
        adaptiveSamples = UVec4Ref(push.adaptiveSamples).v[index];
        uint64_t allocation = uint64_t(adaptiveSamples.y);
        uint64_t roundsEnd = uint64_t(push.sampleStart) + uint64_t(push.sampleCount);
        first = adaptiveSamples.x;
        count = uint(allocation * roundsEnd / uint64_t(push.epochRounds) -
                     allocation * uint64_t(push.sampleStart) / uint64_t(push.epochRounds));
    }
#ifdef PT_BDPT
    bdptPixelIndex = index;
    if (MERGING) {
        vcm = VcmDispatch(push.phase, push.mergeRadius, push.vcmCellMask, push.vcmVerticesPerPixel, push.vcmVertices,
            push.vcmCells, push.vcmPilot, push.vcmPilotMask, push.vcmPilotCell, push.vcmKeepTarget);
        if (push.phase != VCM_PHASE_WHOLE)
            mergeEta = PI * push.mergeRadius * push.mergeRadius * float(scene.imageSize.x * scene.imageSize.y);
        if (push.phase == VCM_PHASE_PILOT) {
            countPilotLightSubpath(pixel);
            return;
        }
        if (push.phase == VCM_PHASE_LIGHT) {
            storeBdptLightSubpath(pixel, first);
            return;
        }
    }
#endif
    PixelSums sums = loadPixelSums(accumulation, base);
    // The stream key once here: a constant table indexed per sample costs a copy of it each time.
    addPixelSamples(pixel, cameraStreamKey(pixel), first, count, push.sampleClamp, sums);
    storePixelSums(accumulation, base, sums);
    // One light path per pixel and sample, splatted wherever it lands.
#ifdef PT_LIGHT_TRACING
    if (lightTracingActive()) traceLightPaths(pixel, first, count);
#endif
    if (push.adaptiveSamples != 0ul) {
        uint rays = closestRaysTraced + shadowRaysTraced;
        adaptiveSamples.x = first + count;
        adaptiveSamples.z = adaptiveSamples.z + min(rays, 0xffffffffu - adaptiveSamples.z); // saturating
        UVec4Ref(push.adaptiveSamples).v[index] = adaptiveSamples;
    }
    if (COUNT_RAYS) {
        UVec4Ref counts = UVec4Ref(push.rayCounts);
        counts.v[index] += uvec4(closestRaysTraced, shadowRaysTraced, 0u, 0u);
    }
}
