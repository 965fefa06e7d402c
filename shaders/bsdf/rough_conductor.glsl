// Rough conductor: GGX microfacet reflection (Walter et al. 2007) with the exact Fresnel
// reflectance of the complex index eta + i k at the microfacet, tinted by the base colour, or for
// a rough MATERIAL_MIRROR (the glTF metal: metallic 1) Schlick's Fresnel with F0 = base colour,
// which is the glTF metallic-roughness model at metallic 1 exactly (shaders/bsdf/gltf_pbr.glsl);
// sampled by the normals visible from wo. Local frame: z is the shading normal on the side of wo.
//   f cos(theta_i) = tint F(wo . wm) D(wm) G2(wo, wi) / (4 cos(theta_o))
//   weight        = tint F G2 / G1(wo)        (D and the Jacobians cancel)
// Sampling computes pdf and weight from the sampled facet (pbrt-v4 does the same) instead of
// evaluating f and the pdf again at wi: the same values up to rounding, for a third of the work.
#ifndef PT_BSDF_ROUGH_CONDUCTOR_GLSL
#define PT_BSDF_ROUGH_CONDUCTOR_GLSL
#include "bsdf/ggx.glsl"
#include "bsdf/fresnel.glsl"
#include "bsdf/bsdf_sample.glsl"

vec3 roughConductorFresnel(GpuMaterial m, float cosI) {
    if (HAS_MIRROR && m.type == MATERIAL_MIRROR) return fresnelSchlick(m.baseColor, cosI);
    return m.baseColor * fresnelConductor(cosI, m.conductorEta, m.conductorK);
}

// f * cos(theta_i) and the pdf of sampling wi, at once: they share the half vector and D (light
// sampling needs both; the driver drops what a caller leaves unused).
vec3 roughConductorEvalPdf(GpuMaterial m, vec3 wo, vec3 wi, out float pdf) {
    pdf = 0.0;
    if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
    vec3 h = wo + wi;
    float len2 = dot(h, h);
    if (!(len2 > 0.0)) return vec3(0.0);
    vec3 wm = h * inversesqrt(len2);
    float cosOM = dot(wo, wm);
    float D = ggxD(wm, m.alpha);
    float lo = ggxSmithL(wo, m.alpha);
    // ggxReflectionPdf: G1(wo) cosOM D / wo.z / (4 cosOM) = D / (2 (wo.z + L(wo))).
    pdf = cosOM > 0.0 && wm.z > 0.0 ? D / (2.0 * (wo.z + lo)) : 0.0;
    vec3 F = roughConductorFresnel(m, clamp(cosOM, 0.0, 1.0));
    return F * (D * ggxG2OverCosO(wo, wi, m.alpha) * 0.25);
}

vec3 roughConductorEval(GpuMaterial m, vec3 wo, vec3 wi) {
    float pdf;
    return roughConductorEvalPdf(m, wo, wi, pdf);
}

float roughConductorPdf(GpuMaterial m, vec3 wo, vec3 wi) {
    float pdf;
    roughConductorEvalPdf(m, wo, wi, pdf);
    return pdf;
}

BsdfSample roughConductorSample(GpuMaterial m, Frame frame, vec3 wo, vec2 u) {
    BsdfSample s = invalidBsdfSample();
    if (wo.z <= 0.0) return s;
    vec3 wm = ggxSampleVisibleNormal(wo, m.alpha, u);
    vec3 wi = reflectAbout(wo, wm);
    if (wi.z <= 0.0) return s; // reflected below the surface: masked, the path ends
    float cosOM = dot(wo, wm);
    if (!(cosOM > 0.0)) return s;
    s.pdf = ggxVisibleNormalPdf(wo, wm, m.alpha) / (4.0 * cosOM);
    if (!(s.pdf > 0.0)) return s;
    s.weight = roughConductorFresnel(m, min(cosOM, 1.0)) * ggxG2OverG1(wo, wi, m.alpha);
    s.wi = toWorld(frame, wi);
    s.valid = true;
    return s;
}

#endif
