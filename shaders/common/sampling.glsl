// Warping of uniform random numbers to distributions, each with its pdf beside it.
#ifndef PT_COMMON_SAMPLING_GLSL
#define PT_COMMON_SAMPLING_GLSL
#include "common/math.glsl"

// Concentric square-to-disk map (Shirley and Chiu 1997): low distortion, keeps stratification.
// Returns the signed radius r and the angle theta; the point is r (cos theta, sin theta).
// u is moved to the middle of its 2^-24 cell, so |r| < 1 always: the rim (u = 0) would give a
// tangent direction of zero pdf, and a path that draws it (1 in 2^23) would end there.
vec2 concentricDiskPolar(vec2 u) {
    vec2 o = 2.0 * u - (1.0 - 1.0 / 16777216.0);
    if (o.x == 0.0 && o.y == 0.0) return vec2(0.0);
    if (abs(o.x) > abs(o.y)) return vec2(o.x, (PI / 4.0) * (o.y / o.x));
    return vec2(o.y, (PI / 2.0) - (PI / 4.0) * (o.x / o.y));
}

vec2 diskPoint(vec2 polar) { return polar.x * vec2(cos(polar.y), sin(polar.y)); }

vec2 sampleConcentricDisk(vec2 u) { return diskPoint(concentricDiskPolar(u)); }

// Cosine-weighted hemisphere around +z (Malley's method); pdf = cos(theta) / pi. The height
// comes from the radius, not from 1 - |disk point|^2: GPU sin and cos are approximate, and
// cos^2 + sin^2 >= 1 would put an interior point on the rim.
vec3 sampleCosineHemisphere(vec2 u) {
    vec2 polar = concentricDiskPolar(u);
    float z = sqrt(max(0.0, (1.0 - polar.x) * (1.0 + polar.x)));
    return vec3(diskPoint(polar), z);
}
float cosineHemispherePdf(float cosTheta) { return max(cosTheta, 0.0) * INV_PI; }

// Uniform hemisphere around +z; pdf = 1 / (2 pi). z = 1 - u.x lies in (0, 1], never tangent.
vec3 sampleUniformHemisphere(vec2 u) {
    float z = 1.0 - u.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = TWO_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}
float uniformHemispherePdf(float cosTheta) { return cosTheta > 0.0 ? 0.5 * INV_PI : 0.0; }

// A uniform point on the unit sphere.
vec3 sampleUniformSphere(vec2 u) {
    float z = 1.0 - 2.0 * u.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = TWO_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Uniform barycentrics on a triangle (the square-root warp); returns (b1, b2).
vec2 sampleUniformTriangle(vec2 u) {
    float su0 = sqrt(u.x);
    return vec2(1.0 - su0, u.y * su0);
}

// Veach's power heuristic with beta = 2, written to stay finite when a pdf is infinite.
float powerHeuristic(float pdfA, float pdfB) {
    if (isinf(pdfA)) return 1.0;
    float a = pdfA * pdfA;
    float b = pdfB * pdfB;
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

#endif
