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

// ---- Spherical triangles: a triangle as seen from a point, on the unit sphere around it ----

// Solid angle of the spherical triangle with unit corners a, b, c (Van Oosterom and Strackee
// 1983): tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a).
float sphericalTriangleArea(vec3 a, vec3 b, vec3 c) {
    return 2.0 * atan(abs(dot(a, cross(b, c))), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
}

// The part of unit vector v orthogonal to unit vector n, normalised.
vec3 orthogonalPart(vec3 v, vec3 n) { return normalize(v - dot(v, n) * n); }

// A direction uniform over the spherical triangle with unit corners a, b, c (Arvo, "Stratified
// Sampling of Spherical Triangles", SIGGRAPH 1995): u.x picks the sub-triangle a, b, c' of area
// u.x times the whole (c' on the arc from a to c), u.y the point on the arc from b to c'.
// `area` is sphericalTriangleArea(a, b, c). Returns vec3(0) where the triangle is too thin for the
// construction (a caller treats that as no sample).
vec3 sampleSphericalTriangle(vec3 a, vec3 b, vec3 c, float area, vec2 u) {
    vec3 nab = cross(a, b), nbc = cross(b, c), nca = cross(c, a);
    if (dot(nab, nab) == 0.0 || dot(nbc, nbc) == 0.0 || dot(nca, nca) == 0.0) return vec3(0.0);
    nab = normalize(nab);
    nca = normalize(nca);
    // The angle at a, between the great circles through it, by its sine and cosine (the area is
    // Van Oosterom and Strackee's). No acos: Mesa lowers it to a polynomial good to 1e-4
    // radians only, which put samples outside the triangle near its edges.
    float cosAlpha = -dot(nab, nca);
    float sinAlpha = length(cross(nab, nca));
    if (!(area > 0.0) || sinAlpha == 0.0) return vec3(0.0);
    // sin and cos of (u.x area - alpha).
    float subArea = u.x * area;
    float sinSub = sin(subArea), cosSub = cos(subArea);
    float s = sinSub * cosAlpha - cosSub * sinAlpha;
    float t = cosSub * cosAlpha + sinSub * sinAlpha;
    float p = t - cosAlpha;
    float q = s + sinAlpha * dot(a, b); // dot(a, b): the cosine of the arc opposite c
    float cosArc = ((q * t - p * s) * cosAlpha - q) / ((q * s + p * t) * sinAlpha);
    // c' lies on the arc from a to c: where the area's rounding would carry it past c, c.
    cosArc = clamp(cosArc, dot(a, c), 1.0);
    vec3 cPrime = cosArc * a + sqrt(max(0.0, 1.0 - cosArc * cosArc)) * orthogonalPart(c, a);
    float z = 1.0 - u.y * (1.0 - dot(cPrime, b));
    vec3 w = z * b + sqrt(max(0.0, 1.0 - z * z)) * orthogonalPart(cPrime, b);
    return allFinite(w) ? w : vec3(0.0);
}

#endif
