// Rough dielectric interface (Walter et al. 2007, "Microfacet Models for Refraction through
// Rough Surfaces"): GGX reflection and refraction, the lobe chosen by the exact Fresnel
// reflectance of the sampled visible microfacet. Transmission is tinted by the base colour
// and carries the 1 / eta^2 radiance scaling, like the smooth dielectric.
// Local frame: z is the shading normal on the FRONT (outside) side, so wo.z < 0 means wo is
// inside the object (eta = 1 / ior); wi on the other side of the surface from wo refracts.
// Everything is computed with both directions flipped to wo's side (the distribution is
// symmetric about the surface plane).
#ifndef PT_BSDF_ROUGH_DIELECTRIC_GLSL
#define PT_BSDF_ROUGH_DIELECTRIC_GLSL
#include "bsdf/ggx.glsl"
#include "bsdf/fresnel.glsl"
#include "bsdf/bsdf_sample.glsl"

// An index ratio this close to 1 is no interface: light passes straight through (the
// refraction half vector wo + eta wi degenerates there).
const float INDEX_MATCHED_EPSILON = 1e-4;

// n_t / n_i seen from wo, and both directions moved to the z > 0 side of wo.
float dielectricSide(float ior, inout vec3 wo, inout vec3 wi) {
    if (wo.z > 0.0) return ior;
    wo.z = -wo.z;
    wi.z = -wi.z;
    return 1.0 / ior;
}

// G2 / cos(theta_o) D (wo . wm) |d wm / d wi| / eta^2: the GGX BTDF times cos(theta_i) without
// its Fresnel factor (Walter et al. eq. 21); wo.z > 0 > wi.z, wm from refractionHalfVector.
float ggxTransmissionNoFresnel(vec3 wo, vec3 wi, vec3 wm, float eta, vec2 alpha) {
    return ggxD(wm, alpha) * ggxG2OverCosO(wo, wi, alpha) * dot(wo, wm) * refractionJacobian(wo, wi, wm, eta) /
           (eta * eta);
}
float ggxTransmissionNoFresnel(vec3 wo, vec3 wi, vec3 wm, float eta, float alpha) {
    return ggxTransmissionNoFresnel(wo, wi, wm, eta, vec2(alpha));
}

// f * |cos(theta_i)| and the pdf of sampling wi, at once: they share the half vector, Fresnel and
// D (light sampling needs both; the driver drops what a caller leaves unused).
vec3 roughDielectricEvalPdf(GpuMaterial m, vec3 wo, vec3 wi, out float pdf) {
    pdf = 0.0;
    if (wo.z == 0.0 || wi.z == 0.0) return vec3(0.0);
    float eta = dielectricSide(m.ior, wo, wi);
    float cosT;
    float lo = ggxSmithL(wo, m.alpha);
    if (wi.z > 0.0) {
        // Both above: wm = normalize(wo + wi) faces both, so ggxReflectionPdf is D / (2 (zo + L(wo))).
        vec3 wm = normalize(wo + wi);
        float F = fresnelDielectric(clamp(dot(wo, wm), 0.0, 1.0), eta, cosT);
        float D = ggxD(wm, m.alpha);
        pdf = F * D / (2.0 * (wo.z + lo));
        return vec3(F * D * ggxG2OverCosO(wo, wi, m.alpha) * 0.25);
    }
    vec3 wm;
    if (!refractionHalfVector(wo, wi, eta, wm)) return vec3(0.0);
    float F = fresnelDielectric(dot(wo, wm), eta, cosT);
    float D = ggxD(wm, m.alpha);
    float jacobian = refractionJacobian(wo, wi, wm, eta);
    float cosOM = dot(wo, wm);
    // ggxVisibleNormalPdf with D shared.
    pdf = (1.0 - F) * (2.0 * cosOM * D / (wo.z + lo)) * jacobian;
    return m.baseColor * ((1.0 - F) * D * ggxG2OverCosO(wo, wi, m.alpha) * cosOM * jacobian / (eta * eta));
}

vec3 roughDielectricEval(GpuMaterial m, vec3 wo, vec3 wi) {
    float pdf;
    return roughDielectricEvalPdf(m, wo, wi, pdf);
}

float roughDielectricPdf(GpuMaterial m, vec3 wo, vec3 wi) {
    float pdf;
    roughDielectricEvalPdf(m, wo, wi, pdf);
    return pdf;
}

BsdfSample roughDielectricSample(GpuMaterial m, Frame frame, vec3 wo, float uLobe, vec2 u) {
    BsdfSample s = invalidBsdfSample();
    if (wo.z == 0.0) return s;
    if (abs(m.ior - 1.0) < INDEX_MATCHED_EPSILON) {
        s.wi = toWorld(frame, -wo);
        s.weight = m.baseColor;
        s.pdf = 1.0;
        s.isDelta = true;
        s.valid = true;
        return s;
    }
    float side = wo.z > 0.0 ? 1.0 : -1.0;
    vec3 woUp = vec3(wo.xy, abs(wo.z));
    float eta = wo.z > 0.0 ? m.ior : 1.0 / m.ior;
    vec3 wm = ggxSampleVisibleNormal(woUp, m.alpha, u);
    float cosT;
    float F = fresnelDielectric(clamp(dot(woUp, wm), 0.0, 1.0), eta, cosT);
    vec3 wi;
    if (uLobe < F) {
        // Reflection (always, under total internal reflection at this facet: F = 1).
        wi = reflectAbout(woUp, wm);
        if (wi.z <= 0.0) return s;
    } else {
        if (!refractAbout(woUp, wm, eta, wi) || wi.z >= 0.0) return s;
        s.etaScale = eta * eta;
    }
    // pdf and weight from the sampled facet (roughDielectricPdf and Eval at wi up to rounding):
    // the lobe's probability F or 1 - F cancels the Fresnel factor of f, D and the Jacobian cancel.
    float cosOM = dot(woUp, wm);
    if (!(cosOM > 0.0)) return s;
    float visible = ggxVisibleNormalPdf(woUp, wm, m.alpha);
    float g2OverG1 = ggxG2OverG1(woUp, wi, m.alpha);
    if (wi.z > 0.0) {
        s.pdf = F * visible / (4.0 * cosOM);
        s.weight = vec3(g2OverG1);
    } else {
        s.pdf = (1.0 - F) * visible * refractionJacobian(woUp, wi, wm, eta);
        s.weight = m.baseColor * (g2OverG1 / (eta * eta));
    }
    if (!(s.pdf > 0.0)) return invalidBsdfSample();
    wi.z *= side; // back to the frame's sides
    s.wi = toWorld(frame, wi);
    s.valid = true;
    return s;
}

#endif
