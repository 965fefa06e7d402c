// The GGX (Trowbridge-Reitz) microfacet distribution: normal distribution D, Smith
// masking G1 and height-correlated masking-shadowing G2 (Heitz 2014, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs"), and sampling of the normals visible
// from wo with the spherical-cap method of Dupuy and Benyoub 2023 ("Sampling Visible GGX
// Normals with Spherical Caps"), which draws exactly Heitz 2018's distribution of visible normals.
// Local frame: z is the macro-surface normal; every routine here wants wo.z >= 0 (callers flip
// to that side first). alpha = perceptual roughness^2, at least MIN_ROUGH_ALPHA.
//
// The formulas are written so the 1 / cos(theta) factors cancel analytically: with
// L(w) = sqrt(z^2 + alpha.x^2 x^2 + alpha.y^2 y^2) (= |z| (1 + 2 Lambda(w))), G1(w) = 2 |z| / (|z| + L(w))
// and G2 = 2 |zo| |zi| / (L(wo) |zi| + L(wi) |zo|) stay finite at grazing angles.
#ifndef PT_BSDF_GGX_GLSL
#define PT_BSDF_GGX_GLSL
#include "common/math.glsl"

// Anisotropic in general (KHR_materials_anisotropy): alpha.x is the roughness along the local x
// axis, alpha.y along y; the isotropic forms (a float alpha) are the same with both equal.

// D(wm) = 1 / (pi ax ay (x^2 / ax^2 + y^2 / ay^2 + z^2)^2), multiplied through by (ax ay)^2 so
// nothing divides by a small alpha; isotropic, alpha^2 / (pi (x^2 + y^2 + alpha^2 z^2)^2), whose
// sum x^2 + y^2 avoids the cancellation of 1 - z^2 near the normal, where D peaks at
// 1 / (pi alpha^2).
float ggxD(vec3 wm, vec2 alpha) {
    float axy = alpha.x * alpha.y;
    vec3 f = vec3(alpha.y * wm.x, alpha.x * wm.y, axy * wm.z);
    float t = dot(f, f);
    return t > 0.0 ? axy * axy * axy / (PI * t * t) : 0.0;
}

// |z| (1 + 2 Lambda(w)), the Smith term without its 1 / cos(theta).
float ggxSmithL(vec3 w, vec2 alpha) {
    vec2 s = alpha * w.xy;
    return sqrt(w.z * w.z + dot(s, s));
}

float ggxG1(vec3 w, vec2 alpha) {
    float z = abs(w.z);
    float denom = z + ggxSmithL(w, alpha);
    return denom > 0.0 ? 2.0 * z / denom : 0.0;
}

// Height-correlated masking-shadowing divided by |wo.z|: G2 / |cos(theta_o)|. Reflection and
// transmission both need G2 over cos(theta_o), and this form is finite when wo is grazing.
float ggxG2OverCosO(vec3 wo, vec3 wi, vec2 alpha) {
    float denom = ggxSmithL(wo, alpha) * abs(wi.z) + ggxSmithL(wi, alpha) * abs(wo.z);
    return denom > 0.0 ? 2.0 * abs(wi.z) / denom : 0.0;
}

// A microfacet normal distributed as the normals visible from wo (wo.z >= 0):
// D_wo(wm) = G1(wo) max(0, wo . wm) D(wm) / wo.z. Stretch wo to the alpha = 1 configuration,
// where the visible normals are the sum of wo and a uniform point on the spherical cap
// z > -wo.z of the unit sphere, then unstretch.
vec3 ggxSampleVisibleNormal(vec3 wo, vec2 alpha, vec2 u) {
    vec3 woStd = normalize(vec3(alpha * wo.xy, wo.z));
    float phi = TWO_PI * u.x;
    float z = (1.0 - u.y) * (1.0 + woStd.z) - woStd.z;
    float sinTheta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
    vec3 h = vec3(sinTheta * cos(phi), sinTheta * sin(phi), z) + woStd;
    vec3 wm = vec3(alpha * h.xy, max(h.z, 0.0));
    float len2 = dot(wm, wm);
    return len2 > 0.0 ? wm * inversesqrt(len2) : vec3(0.0, 0.0, 1.0);
}

// The density of ggxSampleVisibleNormal, per solid angle of wm. G1(wo) / wo.z = 2 / (wo.z + L(wo)).
float ggxVisibleNormalPdf(vec3 wo, vec3 wm, vec2 alpha) {
    float cosOM = dot(wo, wm);
    if (cosOM <= 0.0 || wm.z <= 0.0) return 0.0;
    float denom = wo.z + ggxSmithL(wo, alpha);
    return denom > 0.0 ? 2.0 * cosOM * ggxD(wm, alpha) / denom : 0.0;
}

// Solid-angle pdf of wi = reflect(wo) about a visible normal: D_wo(wm) / (4 |wo . wm|)
// (the Jacobian of the half-vector map, Walter et al. 2007 eq. 14).
float ggxReflectionPdf(vec3 wo, vec3 wi, vec2 alpha) {
    vec3 h = wo + wi;
    float len2 = dot(h, h);
    if (wo.z <= 0.0 || wi.z <= 0.0 || !(len2 > 0.0)) return 0.0;
    vec3 wm = h * inversesqrt(len2);
    float cosOM = dot(wo, wm);
    return cosOM > 0.0 ? ggxVisibleNormalPdf(wo, wm, alpha) / (4.0 * cosOM) : 0.0;
}

// G2(wo, wi) / G1(wo), the weight f cos / pdf of a direction made from a visible normal (the D,
// Fresnel and Jacobian factors cancel): |zi| (zo + L(wo)) / (L(wo) |zi| + L(wi) zo), wo.z > 0.
float ggxG2OverG1(vec3 wo, vec3 wi, vec2 alpha) {
    float zi = abs(wi.z), lo = ggxSmithL(wo, alpha);
    float denom = lo * zi + ggxSmithL(wi, alpha) * wo.z;
    return denom > 0.0 ? zi * (wo.z + lo) / denom : 0.0;
}

// The isotropic forms.
float ggxD(vec3 wm, float alpha) { return ggxD(wm, vec2(alpha)); }
float ggxSmithL(vec3 w, float alpha) { return ggxSmithL(w, vec2(alpha)); }
float ggxG1(vec3 w, float alpha) { return ggxG1(w, vec2(alpha)); }
float ggxG2OverCosO(vec3 wo, vec3 wi, float alpha) { return ggxG2OverCosO(wo, wi, vec2(alpha)); }
float ggxG2(vec3 wo, vec3 wi, float alpha) { return ggxG2OverCosO(wo, wi, vec2(alpha)) * abs(wo.z); }
vec3 ggxSampleVisibleNormal(vec3 wo, float alpha, vec2 u) { return ggxSampleVisibleNormal(wo, vec2(alpha), u); }
float ggxVisibleNormalPdf(vec3 wo, vec3 wm, float alpha) { return ggxVisibleNormalPdf(wo, wm, vec2(alpha)); }
float ggxReflectionPdf(vec3 wo, vec3 wi, float alpha) { return ggxReflectionPdf(wo, wi, vec2(alpha)); }
float ggxG2OverG1(vec3 wo, vec3 wi, float alpha) { return ggxG2OverG1(wo, wi, vec2(alpha)); }

// Mirror reflection of wo about wm (both pointing away from the surface).
vec3 reflectAbout(vec3 wo, vec3 wm) { return 2.0 * dot(wo, wm) * wm - wo; }

// Refraction of wo through a facet wm (wo . wm > 0) into a medium of relative index
// eta = n_t / n_i. False under total internal reflection.
bool refractAbout(vec3 wo, vec3 wm, float eta, out vec3 wi) {
    float cosI = dot(wo, wm);
    float sin2T = max(0.0, 1.0 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0) {
        wi = vec3(0.0);
        return false;
    }
    float cosT = sqrt(1.0 - sin2T);
    wi = normalize(-wo / eta + (cosI / eta - cosT) * wm);
    return true;
}

// The facet normal that refracts wo (wo.z > 0) into wi (wi.z < 0) for eta = n_t / n_i:
// wm ~ wo + eta wi (Walter et al. 2007 eq. 16), turned to +z. False when no facet facing both
// directions does it (then the BTDF is zero there).
bool refractionHalfVector(vec3 wo, vec3 wi, float eta, out vec3 wm) {
    wm = wo + eta * wi;
    float len2 = dot(wm, wm);
    if (!(len2 > 0.0)) return false;
    wm *= inversesqrt(len2);
    if (wm.z < 0.0) wm = -wm;
    return wm.z > 0.0 && dot(wo, wm) > 0.0 && dot(wi, wm) < 0.0;
}

// |d wm / d wi| for refraction (Walter et al. 2007 eq. 17, with eta = n_t / n_i):
// |wi . wm| / (wi . wm + (wo . wm) / eta)^2 (divided through by eta^2).
float refractionJacobian(vec3 wo, vec3 wi, vec3 wm, float eta) {
    float denom = dot(wi, wm) + dot(wo, wm) / eta;
    return denom != 0.0 ? abs(dot(wi, wm)) / (denom * denom) : 0.0;
}

#endif
