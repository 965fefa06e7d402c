// Rough conductor: GGX microfacet reflection (Walter et al. 2007) with the exact Fresnel
// reflectance of the complex index eta + i k at the microfacet, tinted by the base colour;
// sampled by the normals visible from wo. Local frame: z is the shading normal on the side of wo.
//   f cos(theta_i) = tint F(wo . wm) D(wm) G2(wo, wi) / (4 cos(theta_o))
//   weight        = tint F G2 / G1(wo)        (D and the Jacobians cancel)
#ifndef PT_BSDF_ROUGH_CONDUCTOR_GLSL
#define PT_BSDF_ROUGH_CONDUCTOR_GLSL
#include "bsdf/ggx.glsl"
#include "bsdf/fresnel.glsl"
#include "bsdf/bsdf_sample.glsl"

vec3 roughConductorEval(GpuMaterial m, vec3 wo, vec3 wi) {
    if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
    vec3 wm = normalize(wo + wi);
    vec3 F = fresnelConductor(clamp(dot(wo, wm), 0.0, 1.0), m.conductorEta, m.conductorK);
    return m.baseColor * F * (ggxD(wm, m.alpha) * ggxG2OverCosO(wo, wi, m.alpha) * 0.25);
}

float roughConductorPdf(GpuMaterial m, vec3 wo, vec3 wi) { return ggxReflectionPdf(wo, wi, m.alpha); }

BsdfSample roughConductorSample(GpuMaterial m, Frame frame, vec3 wo, vec2 u) {
    BsdfSample s = invalidBsdfSample();
    if (wo.z <= 0.0) return s;
    vec3 wm = ggxSampleVisibleNormal(wo, m.alpha, u);
    vec3 wi = reflectAbout(wo, wm);
    if (wi.z <= 0.0) return s; // reflected below the surface: masked, the path ends
    s.pdf = roughConductorPdf(m, wo, wi);
    if (!(s.pdf > 0.0)) return s;
    s.weight = roughConductorEval(m, wo, wi) / s.pdf;
    s.wi = toWorld(frame, wi);
    s.valid = true;
    return s;
}

#endif
