// The non-delta surfaces (Lambert, course glossy BRDFs) behind one interface, so light
// sampling and MIS treat them alike. Local frame: z is the shading normal on the side of wo.
#ifndef PT_BSDF_SURFACE_BSDF_GLSL
#define PT_BSDF_SURFACE_BSDF_GLSL
#include "bsdf/lambert.glsl"
#include "bsdf/glossy.glsl"
#include "integrator/features.glsl"

bool isSurfaceBsdf(GpuMaterial m) {
    return (HAS_DIFFUSE && m.type == MATERIAL_DIFFUSE) || (HAS_GLOSSY && m.type == MATERIAL_GLOSSY);
}

// f * cos(theta_i)
vec3 surfaceEval(GpuMaterial m, vec3 wo, vec3 wi) {
    if (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) return glossyEval(m, wo, wi);
    return lambertEval(m.baseColor, wo, wi);
}

float surfacePdf(GpuMaterial m, vec3 wo, vec3 wi) {
    if (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) return glossyPdf(m, wo, wi);
    return lambertPdf(wo, wi);
}

BsdfSample surfaceSample(GpuMaterial m, Frame frame, vec3 wo, float uLobe, vec2 u) {
    if (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) return glossySample(m, frame, wo, uLobe, u);
    return lambertSample(m.baseColor, frame, wo, u);
}

#endif
