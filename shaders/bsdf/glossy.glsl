// The CENG795 course's BRDFs: a Lambertian term kd / pi plus one specular lobe of exponent p
// (docs/ceng795-format.md section 5). Local frame: z is the shading normal on the side of wo.
//   Original Phong         ks cos^p(alpha_r) / cos(theta_i)
//   Original Blinn-Phong   ks cos^p(alpha_h) / cos(theta_i)
//   Modified Phong         ks cos^p(alpha_r)  [x (p + 2) / (2 pi) when normalised]
//   Modified Blinn-Phong   ks cos^p(alpha_h)  [x (p + 8) / (8 pi) when normalised]
//   Torrance-Sparrow       ks D F G / (4 cos(theta_i) cos(theta_o)), D = (p + 2) / (2 pi) cos^p(alpha_h),
//                          F from the material's complex index, diffuse x (1 - F) with kdfresnel
// Importance sampling picks the diffuse or the specular lobe by their reflectance weights; the
// specular lobe is sampled as a cosine power around the mirror direction (Phong) or of the
// half vector around the normal (Blinn-Phong, Torrance-Sparrow). The course's mirror with
// layers adds a perfect mirror of reflectance km (m.mirror) to all of this: a delta lobe,
// picked by its weight too and returned with isDelta and that probability as its pdf; eval and
// pdf describe the rest, the pdf scaled by the probability of not picking the mirror.
#ifndef PT_BSDF_GLOSSY_GLSL
#define PT_BSDF_GLOSSY_GLSL
#include "common/math.glsl"
#include "common/sampling.glsl"
#include "bsdf/bsdf_sample.glsl"
#include "bsdf/fresnel.glsl"
#include "shared/features.glsl"

bool glossyIsPhong(GpuMaterial m) {
    return m.glossyModel == GLOSSY_ORIGINAL_PHONG || m.glossyModel == GLOSSY_MODIFIED_PHONG;
}

// Probability of sampling the mirror lobe (0 without one).
float glossyMirrorProbability(GpuMaterial m) {
    float k = luminance(m.mirror);
    if (!(k > 0.0)) return 0.0;
    return k / (k + luminance(m.baseColor) + luminance(m.specular));
}

// Probability of sampling the specular lobe, once the mirror is not picked.
float glossySpecularProbability(GpuMaterial m) {
    float d = luminance(m.baseColor);
    float s = luminance(m.specular);
    return d + s > 0.0 ? s / (d + s) : 0.0;
}

vec3 glossyEval(GpuMaterial m, vec3 wo, vec3 wi) {
    if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
    float p = m.exponent;
    vec3 diffuse = m.baseColor * INV_PI;
    vec3 specular;
    if (m.glossyModel == GLOSSY_TORRANCE_SPARROW) {
        vec3 h = normalize(wo + wi);
        float cosH = h.z;
        float woh = dot(wo, h);
        float D = (p + 2.0) * (0.5 * INV_PI) * pow(max(cosH, 0.0), p);
        float G = min(1.0, min(2.0 * cosH * wo.z / woh, 2.0 * cosH * wi.z / woh));
        vec3 F = fresnelConductor(woh, m.conductorEta, m.conductorK);
        specular = m.specular * D * F * G / (4.0 * wi.z * wo.z);
        if ((m.flags & MATERIAL_FLAG_KD_FRESNEL) != 0u)
            diffuse *= vec3(1.0) - fresnelConductor(wi.z, m.conductorEta, m.conductorK);
    } else {
        float cosAlpha = glossyIsPhong(m) ? dot(vec3(-wi.xy, wi.z), wo) : normalize(wo + wi).z;
        float lobe = pow(max(cosAlpha, 0.0), p);
        if (m.glossyModel == GLOSSY_ORIGINAL_PHONG || m.glossyModel == GLOSSY_ORIGINAL_BLINN_PHONG) {
            lobe /= wi.z;
        } else if ((m.flags & MATERIAL_FLAG_NORMALIZED) != 0u) {
            lobe *= m.glossyModel == GLOSSY_MODIFIED_PHONG ? (p + 2.0) * (0.5 * INV_PI) : (p + 8.0) * (0.125 * INV_PI);
        }
        specular = m.specular * lobe;
    }
    return (diffuse + specular) * wi.z;
}

// Solid-angle pdf of the specular lobe's sampler.
float glossySpecularPdf(GpuMaterial m, vec3 wo, vec3 wi) {
    float p = m.exponent;
    if (glossyIsPhong(m)) {
        float cosAlpha = dot(vec3(-wo.xy, wo.z), wi);
        return cosAlpha > 0.0 ? (p + 1.0) * (0.5 * INV_PI) * pow(cosAlpha, p) : 0.0;
    }
    vec3 h = normalize(wo + wi);
    float woh = dot(wo, h);
    if (h.z <= 0.0 || woh <= 0.0) return 0.0;
    return (p + 1.0) * (0.5 * INV_PI) * pow(h.z, p) / (4.0 * woh);
}

float glossyPdf(GpuMaterial m, vec3 wo, vec3 wi) {
    if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
    float notMirror = 1.0 - glossyMirrorProbability(m);
    if (!COSINE_SAMPLING) return notMirror * uniformHemispherePdf(wi.z);
    float ps = glossySpecularProbability(m);
    return notMirror * ((1.0 - ps) * cosineHemispherePdf(wi.z) + ps * glossySpecularPdf(m, wo, wi));
}

// A direction with density (p + 1) / (2 pi) cos^p around +z.
vec3 sampleCosinePower(vec2 u, float p) {
    float cosTheta = pow(u.x, 1.0 / (p + 1.0));
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    float phi = TWO_PI * u.y;
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

BsdfSample glossySample(GpuMaterial m, Frame frame, vec3 wo, float uLobe, vec2 u) {
    BsdfSample s = invalidBsdfSample();
    if (wo.z <= 0.0) return s;
    float pm = glossyMirrorProbability(m);
    if (uLobe < pm) {
        s.wi = toWorld(frame, vec3(-wo.xy, wo.z));
        s.weight = m.mirror / pm;
        s.pdf = pm;
        s.isDelta = true;
        s.valid = true;
        return s;
    }
    uLobe = (uLobe - pm) / (1.0 - pm); // uniform again over the other lobes
    vec3 wi;
    if (!COSINE_SAMPLING) {
        wi = sampleUniformHemisphere(u);
    } else if (uLobe < glossySpecularProbability(m)) {
        vec3 local = sampleCosinePower(u, m.exponent);
        if (glossyIsPhong(m)) {
            wi = toWorld(makeFrame(vec3(-wo.xy, wo.z)), local); // around the mirror direction
        } else {
            wi = 2.0 * dot(wo, local) * local - wo; // reflect wo about the sampled half vector
        }
    } else {
        wi = sampleCosineHemisphere(u);
    }
    if (wi.z <= 0.0) return s; // below the surface: f = 0 there, the path ends
    s.pdf = glossyPdf(m, wo, wi);
    if (!(s.pdf > 0.0)) return s;
    s.weight = glossyEval(m, wo, wi) / s.pdf;
    s.wi = toWorld(frame, wi);
    s.valid = true;
    return s;
}

#endif
