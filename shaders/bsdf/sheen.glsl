// The KHR_materials_sheen lobe: microfibres standing on the surface, a microfacet BRDF with the
// "Charlie" distribution of Conty Estevez and Kulla 2017 ("Production Friendly Microfacet Sheen
// BRDF"), D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi), alpha = sheenRoughness^2 (as the
// Khronos sample viewer), Fresnel 1, and Smith's height-correlated masking-shadowing
// G2 = 1 / (1 + Lambda(wo) + Lambda(wi)):
//   f cos(theta_i) = sheenColor D(h) / (4 cos(theta_o) (1 + Lambda(wo) + Lambda(wi)))
// Lambda comes from the distribution's projected area A (Lambda = A / cos - 1), tabulated by
// tools/make_sheen_tables.py (src/flatten/sheen_tables.h), instead of the closed-form fit the extension's text gives: that
// fit holds for alpha >= ~0.1 (within 2-7% there) and below it gives up to 2.5x too small a
// Lambda, so a lobe of low roughness would reflect up to 2.7x what arrives at grazing angles.
// With the exact Lambda the lobe's albedo E(cos theta_o, roughness) <= 1, tabulated beside it
// for the layer's albedo scaling (shaders/bsdf/pbr_layers.glsl).
//
// Roughness is clamped to SHEEN_MIN_ROUGHNESS: below it the distribution is a spike at the
// horizon that no table resolves. Sampling: uniform over the hemisphere, as the lobe is broad and
// peaks at grazing angles where cosine sampling puts few directions.
// Local frame: z is the shading normal on the side of wo, wo.z > 0.
#ifndef PT_BSDF_SHEEN_GLSL
#define PT_BSDF_SHEEN_GLSL
#include "common/math.glsl"
#include "common/buffers.glsl"

const float SHEEN_MIN_ROUGHNESS = 0.07; // as tools/make_sheen_tables.py

float sheenAlpha(float roughness) {
    float r = max(roughness, SHEEN_MIN_ROUGHNESS);
    return r * r;
}

float charlieD(float cosH, float alpha) {
    float sin2 = max(1.0 - cosH * cosH, 0.0);
    return (2.0 + 1.0 / alpha) * pow(sin2, 0.5 / alpha) * (0.5 * INV_PI);
}

// Bilinear lookup in one of the sheen tables (0: projected area, 1: albedo; float bits in the
// texel buffer, src/flatten/sheen_tables.h) at (cos theta, roughness), both clamped to [0, 1].
float sheenTable(uint table, float cosTheta, float roughness) {
    const uint size = SHEEN_TABLE_SIZE;
    UintRef texels = UintRef(scene.texels);
    uint first = scene.sheenTables + table * size * size;
    vec2 x = clamp(vec2(cosTheta, roughness), 0.0, 1.0) * float(size - 1u);
    uvec2 i0 = min(uvec2(x), uvec2(size - 2u));
    vec2 t = x - vec2(i0);
    uint row = first + i0.y * size + i0.x;
    float a = mix(uintBitsToFloat(texels.v[row]), uintBitsToFloat(texels.v[row + 1u]), t.x);
    float b = mix(uintBitsToFloat(texels.v[row + size]), uintBitsToFloat(texels.v[row + size + 1u]), t.x);
    return mix(a, b, t.y);
}

// The lobe's directional albedo with sheen colour 1.
float sheenAlbedo(float cosTheta, float roughness) { return sheenTable(1u, cosTheta, roughness); }

// cos(theta) (1 + Lambda): the projected area, which keeps the 1 / cos(theta) of Lambda out of
// the formula below so it stays finite at grazing angles.
float sheenProjectedArea(float cosTheta, float roughness) { return sheenTable(0u, cosTheta, roughness); }

// f cos(theta_i) / sheenColor for wo.z > 0, wi.z > 0:
// D / (4 cos_o (1 + Lambda_o + Lambda_i)) = D cos_i / (4 (A_o cos_i + A_i cos_o - cos_o cos_i)).
float sheenEval(vec3 wo, vec3 wi, float roughness) {
    if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
    vec3 h = normalize(wo + wi);
    float denom = sheenProjectedArea(wo.z, roughness) * wi.z + sheenProjectedArea(wi.z, roughness) * wo.z - wo.z * wi.z;
    return denom > 0.0 ? charlieD(h.z, sheenAlpha(roughness)) * wi.z / (4.0 * denom) : 0.0;
}

#endif
