// Ken Perlin's improved noise (SIGGRAPH 2002): gradients from a permutation of 0..255 at the
// lattice corners, blended with the quintic 6t^5 - 15t^4 + 10t^3. Values lie in about [-1, 1].
// The course's Perlin textures use this noise at the world-space point times NoiseScale.
#ifndef PT_TEXTURES_PERLIN_GLSL
#define PT_TEXTURES_PERLIN_GLSL

// A fixed pseudo-random permutation of 0..255 (an integer hash with period 256 per axis keeps
// the noise tileable like the table version while needing no table in memory).
uint perlinHash(uint x) {
    x = (x & 255u) * 0x9E3779B1u;
    x ^= x >> 15;
    x *= 0x85EBCA77u;
    x ^= x >> 13;
    return x & 255u;
}

uint perlinCorner(ivec3 c) { return perlinHash(uint(c.x) + perlinHash(uint(c.y) + perlinHash(uint(c.z)))); }

// Dot product with one of the 12 edge-midpoint gradients of the cube (Perlin 2002).
float perlinGradient(uint h, vec3 d) {
    h &= 15u;
    float u = h < 8u ? d.x : d.y;
    float v = h < 4u ? d.y : (h == 12u || h == 14u ? d.x : d.z);
    return ((h & 1u) == 0u ? u : -u) + ((h & 2u) == 0u ? v : -v);
}

vec3 perlinFade(vec3 t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

float perlinNoise(vec3 p) {
    vec3 cell = floor(p);
    ivec3 i = ivec3(cell);
    vec3 f = p - cell;
    vec3 w = perlinFade(f);
    float n000 = perlinGradient(perlinCorner(i), f);
    float n100 = perlinGradient(perlinCorner(i + ivec3(1, 0, 0)), f - vec3(1, 0, 0));
    float n010 = perlinGradient(perlinCorner(i + ivec3(0, 1, 0)), f - vec3(0, 1, 0));
    float n110 = perlinGradient(perlinCorner(i + ivec3(1, 1, 0)), f - vec3(1, 1, 0));
    float n001 = perlinGradient(perlinCorner(i + ivec3(0, 0, 1)), f - vec3(0, 0, 1));
    float n101 = perlinGradient(perlinCorner(i + ivec3(1, 0, 1)), f - vec3(1, 0, 1));
    float n011 = perlinGradient(perlinCorner(i + ivec3(0, 1, 1)), f - vec3(0, 1, 1));
    float n111 = perlinGradient(perlinCorner(i + ivec3(1, 1, 1)), f - vec3(1, 1, 1));
    return mix(mix(mix(n000, n100, w.x), mix(n010, n110, w.x), w.y),
        mix(mix(n001, n101, w.x), mix(n011, n111, w.x), w.y), w.z);
}

#endif
