// The non-delta surfaces (Lambert, course glossy BRDFs, GGX-rough conductors and dielectrics,
// the glTF metallic-roughness material) behind one interface, so light sampling and MIS treat
// them alike. Local frame: z is the shading normal on the side of wo, except for transmissive
// surfaces (isTransmissiveSurface), whose z is the front-side shading normal (wo.z < 0: inside).
// Every branch sits behind its specialization constant: a kernel without microfacet or PBR
// materials compiles none of their code.
#ifndef PT_BSDF_SURFACE_BSDF_GLSL
#define PT_BSDF_SURFACE_BSDF_GLSL
#include "bsdf/lambert.glsl"
#include "bsdf/glossy.glsl"
#include "bsdf/rough_conductor.glsl"
#include "bsdf/rough_dielectric.glsl"
#include "bsdf/gltf_pbr.glsl"
#include "bsdf/mirror.glsl"
#include "bsdf/conductor.glsl"
#include "geometry/interaction.glsl"
#include "shared/features.glsl"

// GGX-rough conductor or dielectric (alpha 0 keeps the smooth delta models). A rough mirror is
// the glTF metal (Schlick's Fresnel from the base colour), a conductor of its own Fresnel.
bool isRough(GpuMaterial m) { return HAS_MICROFACET && m.alpha > 0.0; }
bool isRoughConductor(GpuMaterial m) {
    return isRough(m) && ((HAS_CONDUCTOR && m.type == MATERIAL_CONDUCTOR) || (HAS_MIRROR && m.type == MATERIAL_MIRROR));
}
bool isRoughDielectric(GpuMaterial m) { return HAS_DIELECTRIC && isRough(m) && m.type == MATERIAL_DIELECTRIC; }
bool isPbr(GpuMaterial m) { return HAS_PBR && m.type == MATERIAL_PBR; }

// Surfaces that both sides of shade (light passes through them).
bool isTransmissiveSurface(GpuMaterial m) {
    return isRoughDielectric(m) ||
           (isPbr(m) && (m.transmission > 0.0 || (HAS_DIFFUSE_TRANSMISSION && m.diffuseTransmission > 0.0)));
}

bool isSurfaceBsdf(GpuMaterial m) {
    return (HAS_DIFFUSE && m.type == MATERIAL_DIFFUSE) || (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) || isPbr(m) ||
           isRoughConductor(m) || isRoughDielectric(m);
}

// f * |cos(theta_i)|
vec3 surfaceEval(GpuMaterial m, vec3 wo, vec3 wi) {
    if (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) return glossyEval(m, wo, wi);
    if (isPbr(m)) return pbrEval(m, wo, wi);
    if (isRoughConductor(m)) return roughConductorEval(m, wo, wi);
    if (isRoughDielectric(m)) return roughDielectricEval(m, wo, wi);
    return lambertEval(m.baseColor, wo, wi);
}

float surfacePdf(GpuMaterial m, vec3 wo, vec3 wi) {
    if (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) return glossyPdf(m, wo, wi);
    if (isPbr(m)) return pbrPdf(m, wo, wi);
    if (isRoughConductor(m)) return roughConductorPdf(m, wo, wi);
    if (isRoughDielectric(m)) return roughDielectricPdf(m, wo, wi);
    return lambertPdf(wo, wi);
}

// surfaceEval and surfacePdf at once, for light sampling: the microfacet BSDFs share their
// half vector, Fresnel and D between the two.
vec3 surfaceEvalPdf(GpuMaterial m, vec3 wo, vec3 wi, out float pdf) {
    if (isRoughConductor(m)) return roughConductorEvalPdf(m, wo, wi, pdf);
    if (isRoughDielectric(m)) return roughDielectricEvalPdf(m, wo, wi, pdf);
    pdf = surfacePdf(m, wo, wi);
    return surfaceEval(m, wo, wi);
}

BsdfSample surfaceSample(GpuMaterial m, Frame frame, vec3 wo, float uLobe, vec2 u) {
    if (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) return glossySample(m, frame, wo, uLobe, u);
    if (isPbr(m)) return pbrSample(m, frame, wo, uLobe, u);
    if (isRoughConductor(m)) return roughConductorSample(m, frame, wo, u);
    if (isRoughDielectric(m)) return roughDielectricSample(m, frame, wo, uLobe, u);
    return lambertSample(m.baseColor, frame, wo, u);
}

// The frame a surface shades in, seen from the side the ray arrived on (si.frontFace). Rough
// dielectrics and PBR transmission (transmissive): both sides shade, light crosses the surface,
// and the frame keeps the front-side normal (wo.z < 0 inside). Opaque surfaces: one-sided ones
// are black from behind (false), double-sided ones turn to the viewer's side (si with them).
bool surfaceFrame(inout SurfaceInteraction si, inout GpuMaterial mat, out Frame frame) {
    bool transmissive = isTransmissiveSurface(mat);
    if (!transmissive && !si.frontFace && (mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) == 0u) return false;
    frame = makeFrame(transmissive || si.frontFace ? si.ns : -si.ns);
    orientMaterialFrame(frame, mat);
    if (!transmissive && !si.frontFace) turnToBackSide(si);
    return true;
}

// The bounce off a smooth mirror or conductor (every lobe a delta); invalid for other surfaces.
BsdfSample smoothReflectorSample(GpuMaterial mat, Frame frame, vec3 wo) {
    if (HAS_MIRROR && mat.type == MATERIAL_MIRROR && !isRoughConductor(mat))
        return mirrorSample(mat.baseColor, frame, wo);
    if (HAS_CONDUCTOR && mat.type == MATERIAL_CONDUCTOR && !isRoughConductor(mat))
        return conductorSample(mat.baseColor, mat.conductorEta, mat.conductorK, frame, wo);
    return invalidBsdfSample();
}

bool isSmoothReflector(GpuMaterial mat) {
    return ((HAS_MIRROR && mat.type == MATERIAL_MIRROR) || (HAS_CONDUCTOR && mat.type == MATERIAL_CONDUCTOR)) &&
           !isRoughConductor(mat);
}

#endif
