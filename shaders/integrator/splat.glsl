// Splats: contributions of light paths (and of bidirectional connections to the camera) added
// to the pixel they land in, wherever that is, as 64-bit fixed-point integer sums (SPLAT_* in
// shared/layout.h). Integer atomics make the sums independent of the order of arrival, so the
// image is the same however the work is split, checkpointed or merged.
#ifndef PT_INTEGRATOR_SPLAT_GLSL
#define PT_INTEGRATOR_SPLAT_GLSL
#extension GL_EXT_shader_atomic_int64 : require
#include "common/buffers.glsl"
#include "common/math.glsl"

layout(buffer_reference, std430, buffer_reference_align = 8) buffer SplatRef { uint64_t v[]; };

// Adds one path's contribution, already divided by the number of pixels, to a pixel's sums.
void splatAdd(uvec2 pixel, vec3 value) {
    if (!allFinite(value)) return;
    uint pixels = scene.imageSize.x * scene.imageSize.y;
    SplatRef splats = SplatRef(scene.accumulation + uint64_t(pixels) * uint64_t(ACCUMULATION_VEC4S_PER_PIXEL * 16u));
    uint base = SPLAT_WORDS_PER_PIXEL * (pixel.y * scene.imageSize.x + pixel.x);
    // Clamped far below the sums' headroom: a single path never overflows them.
    const float maxScaled = 4.0e18;
    for (int c = 0; c < 3; ++c) {
        float v = max(value[c], 0.0);
        if (v <= 0.0) continue;
        atomicAdd(splats.v[base + SPLAT_SUM + uint(c)], uint64_t(min(v * float(SPLAT_SUM_SCALE), maxScaled) + 0.5));
        atomicAdd(splats.v[base + SPLAT_SUM_SQUARES + uint(c)],
            uint64_t(min(v * v * float(SPLAT_SQUARE_SCALE), maxScaled) + 0.5));
    }
}

#endif
