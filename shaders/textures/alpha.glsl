// glTF alpha at a candidate triangle hit, for traversal: MASK cuts out below alphaCutoff; BLEND
// is a stochastic cut-out (kept with probability alpha), an unbiased stand-in for blending
// that needs no sorting. Its random number hashes the ray and the hit, so a given ray always
// gets the same answer (shadow and camera rays agree) and renders stay reproducible.
#ifndef PT_TEXTURES_ALPHA_GLSL
#define PT_TEXTURES_ALPHA_GLSL
#include "common/buffers.glsl"
#include "common/ray.glsl"
#include "textures/texture.glsl"

uint alphaHash(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// True when the hit on triangle `primitive` at barycentrics `bary` is cut away.
bool alphaCutsOut(GpuTriangle tri, uint primitive, vec2 bary, Ray ray) {
    GpuMaterial m = sceneMaterials.v[tri.materialIndex];
    float alpha = m.opacity;
    if (m.baseColorTexture != NO_TEXTURE) {
        GpuTriangleShading sh = sceneShading.v[primitive];
        float b0 = 1.0 - bary.x - bary.y;
        vec2 uv = b0 * vec2(sh.u0, sh.v.x) + bary.x * vec2(sh.u1, sh.v.y) + bary.y * vec2(sh.u2, sh.v.z);
        alpha *= evalTexture(m.baseColorTexture, uv, vec3(0.0)).a;
    }
    if ((m.flags & MATERIAL_FLAG_ALPHA_MASK) != 0u) return alpha < m.alphaCutoff;
    uint h = alphaHash(
        primitive ^ alphaHash(floatBitsToUint(ray.origin.x) ^
                              alphaHash(floatBitsToUint(ray.origin.y) ^
                                        alphaHash(floatBitsToUint(ray.origin.z) ^
                                                  alphaHash(floatBitsToUint(ray.direction.x) ^
                                                            alphaHash(floatBitsToUint(ray.direction.y) ^
                                                                      alphaHash(floatBitsToUint(ray.direction.z))))))));
    return float(h >> 8) * (1.0 / 16777216.0) >= alpha;
}

#endif
