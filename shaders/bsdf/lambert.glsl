// Lambertian reflection. Local frame: z is the shading normal on the side of wo.
#ifndef PT_BSDF_LAMBERT_GLSL
#define PT_BSDF_LAMBERT_GLSL
#include "common/sampling.glsl"
#include "bsdf/bsdf_sample.glsl"
#include "shared/features.glsl"

// f * cos(theta_i) for local directions.
vec3 lambertEval(vec3 albedo, vec3 woLocal, vec3 wiLocal) {
    if (woLocal.z <= 0.0 || wiLocal.z <= 0.0) return vec3(0.0);
    return albedo * (INV_PI * wiLocal.z);
}

float lambertPdf(vec3 woLocal, vec3 wiLocal) {
    if (woLocal.z <= 0.0 || wiLocal.z <= 0.0) return 0.0;
    return COSINE_SAMPLING ? cosineHemispherePdf(wiLocal.z) : uniformHemispherePdf(wiLocal.z);
}

BsdfSample lambertSample(vec3 albedo, Frame frame, vec3 woLocal, vec2 u) {
    if (woLocal.z <= 0.0) return invalidBsdfSample();
    BsdfSample s = invalidBsdfSample();
    vec3 wiLocal = COSINE_SAMPLING ? sampleCosineHemisphere(u) : sampleUniformHemisphere(u);
    if (wiLocal.z <= 0.0) return s;
    s.wi = toWorld(frame, wiLocal);
    s.pdf = lambertPdf(woLocal, wiLocal);
    // Cosine sampling cancels f * cos / pdf down to the albedo exactly.
    s.weight = COSINE_SAMPLING ? albedo : albedo * (2.0 * wiLocal.z);
    s.valid = true;
    return s;
}

#endif
