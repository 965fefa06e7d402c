// KHR_materials_iridescence: the Fresnel reflectance of a base under a thin dielectric film,
// Belcour and Barla 2017 ("A Practical Extension to Microfacet Theory for the Modeling of
// Varying Iridescence") in the approximation the extension's implementation notes give: Schlick
// reflectances at the two interfaces (air or coat / film, film / base), the base's index from its
// F0 (so metals are treated as dielectrics of that F0, without extinction), phase shifts of 0 or
// pi, and the interference terms integrated against the CIE sensitivities in closed form (the
// first two orders, Gaussian fits of the sensitivities' Fourier transforms), turned into linear
// Rec. 709 RGB.
//
// The result is clamped to [0, 1] per channel: the first orders can overshoot by a little, and
// the base below gets 1 - F. (A film thinner than about 30 nm is faded out by the caller: these
// Schlick interfaces do not vanish as the film does.)
#ifndef PT_BSDF_THIN_FILM_GLSL
#define PT_BSDF_THIN_FILM_GLSL
#include "common/math.glsl"
#include "bsdf/fresnel.glsl"

// Linear Rec. 709 from CIE XYZ (columns).
const mat3 XYZ_TO_REC709 =
    mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314, 0.0415560, 1.0572252);

float thinFilmF0(float transmittedIor, float incidentIor) {
    float r = (transmittedIor - incidentIor) / (transmittedIor + incidentIor);
    return r * r;
}

// The CIE sensitivities' Fourier transforms at optical path difference `opd` (nm) with phase
// shift `shift`, as RGB.
vec3 thinFilmSensitivity(float opd, vec3 shift) {
    float phase = TWO_PI * opd * 1.0e-9;
    const vec3 amplitude = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
    const vec3 position = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
    const vec3 variance = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
    vec3 xyz = amplitude * sqrt(TWO_PI * variance) * cos(position * phase + shift) * exp(-phase * phase * variance);
    xyz.x +=
        9.7470e-14 * sqrt(TWO_PI * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) * exp(-4.5282e+09 * phase * phase);
    return XYZ_TO_REC709 * (xyz / 1.0685e-7);
}

// Reflectance at cos(theta) between the incident direction and the (micro)facet normal of a base
// of normal-incidence reflectance baseF0 under a film of index filmIor and thickness `thickness`
// nm, seen from a medium of index outsideIor.
vec3 thinFilmFresnel(float outsideIor, float filmIor, float thickness, vec3 baseF0, float cosTheta) {
    float cos1 = clamp(cosTheta, 0.0, 1.0);
    float sin2Sq = (outsideIor / filmIor) * (outsideIor / filmIor) * (1.0 - cos1 * cos1);
    if (sin2Sq >= 1.0) return vec3(1.0); // total internal reflection at the film
    float cos2 = sqrt(1.0 - sin2Sq);

    // First interface (outside / film) and second (film / base).
    float R12 = fresnelSchlick(vec3(thinFilmF0(filmIor, outsideIor)), cos1).x;
    float T121 = 1.0 - R12;
    vec3 sqrtF0 = sqrt(clamp(baseF0, 0.0, 0.9999));
    vec3 baseIor = (1.0 + sqrtF0) / (1.0 - sqrtF0);
    vec3 R1 = vec3(thinFilmF0(baseIor.x, filmIor), thinFilmF0(baseIor.y, filmIor), thinFilmF0(baseIor.z, filmIor));
    vec3 R23 = fresnelSchlick(R1, cos2);

    // Phase shifts: pi where light reflects off a lower index.
    float phi12 = filmIor < outsideIor ? PI : 0.0;
    vec3 phi23 = vec3(baseIor.x < filmIor ? PI : 0.0, baseIor.y < filmIor ? PI : 0.0, baseIor.z < filmIor ? PI : 0.0);
    vec3 phi = vec3(PI - phi12) + phi23;

    float opd = 2.0 * filmIor * thickness * cos2;
    vec3 R123 = clamp(R12 * R23, 1e-5, 0.9999);
    vec3 r123 = sqrt(R123);
    vec3 Rs = T121 * T121 * R23 / (1.0 - R123);
    vec3 I = R12 + Rs; // the m = 0 term
    vec3 Cm = Rs - T121;
    for (int m = 1; m <= 2; ++m) {
        Cm *= r123;
        I += Cm * 2.0 * thinFilmSensitivity(float(m) * opd, float(m) * phi);
    }
    return clamp(I, 0.0, 1.0);
}

#endif
