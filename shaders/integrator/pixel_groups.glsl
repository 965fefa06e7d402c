// Which pixel each invocation renders, and which pixels share their random numbers under
// SHARED_SAMPLES. Lavapipe runs 8 consecutive invocations as one SIMD vector, and a loop or
// branch costs as much as its slowest lane, so what the 8 pixels of a vector have in common
// decides the speed. (Without shared samples each invocation keeps its pixel: a vector over a
// 4x2 block instead of a row of 8 was measured level on the 1 M-triangle mesh.)
//
// SHARED_SAMPLES (`--shared-samples on`): the path tracer's 8 pixels of a vector take the same
// random numbers, so their paths bounce the same ways, their shadow rays aim at the same light
// points and their lanes stay in step (one path at a time each, not regenerated), which costs far
// fewer divergent iterations. Each pixel's own estimate is as before in distribution (its samples
// are one Owen-scrambled Sobol' sequence), so its expected error is unchanged; but the noise of
// the 8 pixels is correlated. The 8 are spread over an 8x8 block, one in each row and column and
// at least sqrt(5) pixels apart (also across blocks), so that no neighbours share noise and the
// correlation shows as faint mottling at the block's scale rather than as a mosaic
// (bench/RESULTS.md, "Shared samples").
#ifndef PT_INTEGRATOR_PIXEL_GROUPS_GLSL
#define PT_INTEGRATOR_PIXEL_GROUPS_GLSL
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require // workgroupBlock
#include "shared/features.glsl"

// The groups of an 8x8 block: invocation i of the workgroup renders offset SHARED_GROUP_PIXELS[i]
// (y * 8 + x), so group g (invocations 8g..8g+7, one SIMD vector) is entries 8g..8g+7; and
// SHARED_GROUP_OF_OFFSET is its inverse's group. A Latin square with no equal entries closer
// than sqrt(5) on the torus, found by a randomised search.
const uint SHARED_GROUP_PIXELS[64] =
    uint[64](7u, 12u, 22u, 26u, 37u, 40u, 51u, 57u, 1u, 15u, 21u, 27u, 32u, 42u, 52u, 62u, 2u, 14u, 20u, 31u, 33u, 43u,
        48u, 61u, 4u, 8u, 18u, 29u, 35u, 46u, 49u, 63u, 0u, 11u, 17u, 30u, 34u, 45u, 55u, 60u, 3u, 13u, 23u, 25u, 38u,
        44u, 50u, 56u, 5u, 10u, 16u, 28u, 39u, 41u, 54u, 59u, 6u, 9u, 19u, 24u, 36u, 47u, 53u, 58u);
const uint SHARED_GROUP_OF_OFFSET[64] = uint[64](4u, 1u, 2u, 5u, 3u, 6u, 7u, 0u, 3u, 7u, 6u, 4u, 0u, 5u, 2u, 1u, 6u, 4u,
    3u, 7u, 2u, 1u, 0u, 5u, 7u, 5u, 0u, 1u, 6u, 3u, 4u, 2u, 1u, 2u, 4u, 3u, 7u, 0u, 5u, 6u, 0u, 6u, 1u, 2u, 5u, 4u, 3u,
    7u, 2u, 3u, 5u, 0u, 1u, 7u, 6u, 4u, 5u, 0u, 7u, 6u, 4u, 2u, 1u, 3u);

// The 8x8 block of the tile that this workgroup renders: workgroup l (row-major) takes block
// (l * blockStride) mod blocks, a bijection (the stride is coprime with the count), so that each
// lavapipe thread's contiguous run of workgroups spans the whole tile (why: render/workgroup_order.h).
uvec2 workgroupBlock(uint blockStride) {
    uint blocksX = gl_NumWorkGroups.x, blocks = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
    uint linear = gl_WorkGroupID.y * blocksX + gl_WorkGroupID.x;
    uint block = uint((uint64_t(linear) * uint64_t(blockStride)) % uint64_t(blocks));
    return uvec2(block % blocksX, block / blocksX);
}

// The invocation's pixel relative to the tile's origin, for the renderer's 8x8 workgroups
// (Renderer::localSize_).
uvec2 invocationPixel(uint blockStride) {
    uvec2 block = workgroupBlock(blockStride);
    if (!SHARED_SAMPLES) return block * 8u + gl_LocalInvocationID.xy;
    uint offset = SHARED_GROUP_PIXELS[gl_LocalInvocationIndex];
    return block * 8u + uvec2(offset & 7u, offset >> 3u);
}

// The key of a pixel's camera-path random numbers (rngCreate): the pixel, or with shared samples
// its group's, a function of the pixel alone (so the image does not depend on the tiling). The
// top bit keeps group keys apart from every pixel's own (the light tracer's streams).
uvec2 cameraStreamKey(uvec2 pixel) {
    if (!SHARED_SAMPLES) return pixel;
    uint group = SHARED_GROUP_OF_OFFSET[(pixel.y & 7u) * 8u + (pixel.x & 7u)];
    return uvec2((pixel.x >> 3u) * 8u + group, (pixel.y >> 3u) | 0x80000000u);
}

#endif
