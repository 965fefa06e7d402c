// Smooth dielectric interface: reflection or refraction, chosen with the Fresnel probability,
// so the weight is 1 (times the tint and radiance scaling) and never divides by a small pdf.
// Local frame: z is the shading normal on the side of wo. `entering` says whether wo is
// outside the object (geometric front side), which picks eta.
#ifndef PT_BSDF_DIELECTRIC_GLSL
#define PT_BSDF_DIELECTRIC_GLSL
#include "bsdf/fresnel.glsl"
#include "bsdf/bsdf_sample.glsl"

BsdfSample dielectricSample(vec3 tint, float ior, bool entering, Frame frame, vec3 woLocal, float u) {
    BsdfSample s = invalidBsdfSample();
    float cosI = woLocal.z;
    if (cosI <= 0.0) return s;
    float eta = entering ? ior : 1.0 / ior; // n_t / n_i
    float cosT;
    float F = fresnelDielectric(cosI, eta, cosT);
    s.isDelta = true;
    s.valid = true;
    if (u < F) {
        // Reflection (always taken under total internal reflection, where F = 1).
        s.wi = toWorld(frame, vec3(-woLocal.xy, woLocal.z));
        s.weight = vec3(1.0);
        s.pdf = F;
    } else {
        vec3 wiLocal = vec3(-woLocal.xy / eta, -cosT);
        s.wi = normalize(toWorld(frame, wiLocal));
        // Radiance is compressed into a smaller solid angle on entering: scale by 1/eta^2.
        s.weight = tint / (eta * eta);
        s.pdf = 1.0 - F;
        s.etaScale = eta * eta;
    }
    return s;
}

#endif
