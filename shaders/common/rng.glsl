// Counter-based random numbers: every value is a pure function of (pixel, sample index,
// dimension, seed), so images do not depend on dispatch chunking or thread scheduling.
// Hash: PCG4D (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020).
#ifndef PT_COMMON_RNG_GLSL
#define PT_COMMON_RNG_GLSL
#include "shared/layout.h"
#include "shared/features.glsl"
#include "common/sobol.glsl"

// Which points fill the dimensions (SAMPLER, `--sampler`): independent hashes, or
// Owen-scrambled Sobol' (common/sobol.glsl) addressed by the same (pixel, sample, dimension).

uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

struct Rng {
    uvec4 key; // (pixel x, pixel y, sample index, seed)
};

Rng rngCreate(uvec2 pixel, uint sampleIndex, uint seed) {
    Rng r;
    r.key = uvec4(pixel, sampleIndex, seed);
    return r;
}

// Tests only: pin every random number to an end of its range (0 or 1 - 2^-24), so that the
// hard-case tests can show no sampling routine divides by zero or takes a NaN there
// (FORCED_RANDOM, shared/features.h).

// A float in [0, 1 - 2^-24]: the top 24 bits, so 1.0 is never returned.
float uintToUnitFloat(uint x) {
    if (FORCED_RANDOM != FORCED_RANDOM_OFF) return FORCED_RANDOM == FORCED_RANDOM_ZERO ? 0.0 : 1.0 - 1.0 / 16777216.0;
    return float(x >> 8u) * (1.0 / 16777216.0);
}

uvec4 rngHash(Rng r, uint dimension) {
    return pcg4d(uvec4(r.key.xy, r.key.z ^ (dimension * 0x9E3779B9u), r.key.w + dimension));
}

// Random numbers are addressed, not drawn: dimension = camera dimensions, then a fixed block
// per path vertex, so toggling a technique (NEE, RR) never reshuffles the numbers of others.
const uint DIM_PIXEL = 0u; // 2D: jitter inside the pixel
const uint DIM_LENS = 2u;  // 2D: point on the thin lens
const uint DIM_FIRST_BOUNCE = 4u;
// 1D: the camera sample's time for motion blur. Far above any bounce's dimensions, so adding
// motion to a scene leaves every other dimension (and a static scene's image) unchanged.
const uint DIM_TIME = 0x7fffffffu;
// 1D: the wavelength of a path that meets a dispersive material (shaders/common/spectrum.glsl),
// likewise apart.
const uint DIM_WAVELENGTH = 0x7ffffffeu;
const uint DIM_BSDF_LOBE = 0u;      // 1D, offsets inside one vertex's block
const uint DIM_BSDF_DIRECTION = 1u; // 2D
const uint DIM_LIGHT_SELECT = 3u;   // 1D
const uint DIM_LIGHT_POINT = 4u;    // 2D
const uint DIM_ROULETTE = 6u;       // 1D
const uint DIMS_PER_BOUNCE = 7u;

uint bounceDimension(uint bounce, uint offset) { return DIM_FIRST_BOUNCE + bounce * DIMS_PER_BOUNCE + offset; }

// Per-stream seeds of the Sobol' sampler: index shuffle, and the scrambles of its two values.
uvec3 sobolSeeds(Rng r, uint dimension) { return pcg4d(uvec4(r.key.xy, dimension, r.key.w)).xyz; }

// Consecutive bounces' directions as one 4D point: the BSDF direction at an even bounce (2, 4,
// ...) is the upper half (sobolOwenUpper2) of the point whose lower half is the direction at the
// bounce before, so that a path's first two directions are stratified jointly and not only each
// on its own. At equal time 0.93x the relMSE on the diffuse Cornell box and the 1 M-triangle
// mesh, the glass box 1.02x (within the noise), the rough box level (bench/RESULTS.md,
// "Consecutive bounces as 4D Sobol' points"); groups of three or four directions, or a direction
// with the next bounce's light point, gained no more. Every other 2D sample is a stream of its own.
const uint NO_LOWER_DIMENSION = 0xffffffffu;
const uint PAIRED_BOUNCES = 1024u; // far above any path's depth; keeps the light tracer's dimensions out
uint lowerDimensionOf(uint dimension) {
    if (dimension < DIM_FIRST_BOUNCE || dimension >= DIM_FIRST_BOUNCE + PAIRED_BOUNCES * DIMS_PER_BOUNCE)
        return NO_LOWER_DIMENSION;
    uint bounce = (dimension - DIM_FIRST_BOUNCE) / DIMS_PER_BOUNCE;
    uint offset = (dimension - DIM_FIRST_BOUNCE) % DIMS_PER_BOUNCE;
    if (offset != DIM_BSDF_DIRECTION || bounce < 2u || (bounce & 1u) != 0u) return NO_LOWER_DIMENSION;
    return bounceDimension(bounce - 1u, DIM_BSDF_DIRECTION);
}

// The Sobol' sampler's 2D point for `dimension` (rng2 with SAMPLER_SOBOL).
uvec2 sobolPoint2(Rng r, uint dimension) {
    uint lower = lowerDimensionOf(dimension);
    if (lower == NO_LOWER_DIMENSION) return sobolOwen2(r.key.z, sobolSeeds(r, dimension));
    return sobolOwenUpper2(r.key.z, sobolSeeds(r, lower).x, sobolSeeds(r, dimension).yz);
}

float rng1(Rng r, uint dimension) {
    if (SAMPLER == SAMPLER_SOBOL) return uintToUnitFloat(sobolOwen2(r.key.z, sobolSeeds(r, dimension)).x);
    return uintToUnitFloat(rngHash(r, dimension).x);
}

// A 2D sample occupies dimensions d and d + 1; both values come from the hash of d.
vec2 rng2(Rng r, uint dimension) {
    uvec2 h = SAMPLER == SAMPLER_SOBOL ? sobolPoint2(r, dimension) : rngHash(r, dimension).xy;
    return vec2(uintToUnitFloat(h.x), uintToUnitFloat(h.y));
}

#endif
