// Warping of uniform random numbers to distributions, each with its pdf beside it.
#ifndef PT_COMMON_SAMPLING_GLSL
#define PT_COMMON_SAMPLING_GLSL
#include "common/math.glsl"

// Concentric square-to-disk map (Shirley and Chiu 1997): low distortion, keeps stratification.
vec2 sampleConcentricDisk(vec2 u) {
    vec2 o = 2.0 * u - 1.0;
    if (o.x == 0.0 && o.y == 0.0) return vec2(0.0);
    float r, theta;
    if (abs(o.x) > abs(o.y)) {
        r = o.x;
        theta = (PI / 4.0) * (o.y / o.x);
    } else {
        r = o.y;
        theta = (PI / 2.0) - (PI / 4.0) * (o.x / o.y);
    }
    return r * vec2(cos(theta), sin(theta));
}

// Cosine-weighted hemisphere around +z (Malley's method); pdf = cos(theta) / pi.
vec3 sampleCosineHemisphere(vec2 u) {
    vec2 d = sampleConcentricDisk(u);
    float z = sqrt(max(0.0, 1.0 - dot(d, d)));
    return vec3(d, z);
}
float cosineHemispherePdf(float cosTheta) { return max(cosTheta, 0.0) * INV_PI; }

// Uniform hemisphere around +z; pdf = 1 / (2 pi).
vec3 sampleUniformHemisphere(vec2 u) {
    float z = u.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = TWO_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}
float uniformHemispherePdf(float cosTheta) { return cosTheta > 0.0 ? 0.5 * INV_PI : 0.0; }

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
