// Constants and small helpers shared by every shader file.
#ifndef PT_COMMON_MATH_GLSL
#define PT_COMMON_MATH_GLSL

const float PI = 3.14159265358979323846;
const float INV_PI = 0.31830988618379067154;
const float TWO_PI = 6.28318530717958647692;
const float FLOAT_MAX = 3.402823466e+38;

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// min and max for operands that are never NaN, as a compare and a select. GLSL's min and max
// must return the other operand when one is NaN, and lavapipe builds each as four instructions
// (the x86 min or max, a compare for NaN, a blend and a zeroing); a compare and a select is what
// x86's own min and max compute. Where neither operand can be NaN the two agree (but for which
// of +0 and -0 a tie returns: here the second operand). In the traversal's slab tests, which
// run for every child of every node visited, this and choosing each slab's near plane by the
// direction's sign took 3.5% off the 1 M-triangle mesh's time (bench/RESULTS.md, "The slab test
// without NaN-safe min and max").
vec4 minOfNumbers(vec4 a, vec4 b) { return mix(b, a, lessThan(a, b)); }
vec4 maxOfNumbers(vec4 a, vec4 b) { return mix(b, a, greaterThan(a, b)); }
float maxOfNumbers(float a, float b) { return a > b ? a : b; }

// Affine maps stored as the rows of a 3x4 matrix (spheres' and instances' transforms).
vec3 transformPoint(vec4 rows[3], vec3 p) {
    return vec3(dot(rows[0].xyz, p) + rows[0].w, dot(rows[1].xyz, p) + rows[1].w, dot(rows[2].xyz, p) + rows[2].w);
}
vec3 transformVector(vec4 rows[3], vec3 v) {
    return vec3(dot(rows[0].xyz, v), dot(rows[1].xyz, v), dot(rows[2].xyz, v));
}
// A normal under the map whose inverse is `inverseRows`: the inverse transpose, i.e. the
// columns of the inverse's linear part (not renormalised).
vec3 transformNormal(vec4 inverseRows[3], vec3 n) {
    return inverseRows[0].xyz * n.x + inverseRows[1].xyz * n.y + inverseRows[2].xyz * n.z;
}

// a * b - c * d with a single rounding error (Kahan's algorithm with fused multiply-adds, as
// pbrt-v4's DifferenceOfProducts).
float differenceOfProducts(float a, float b, float c, float d) {
    precise float cd = c * d;
    precise float err = fma(-c, d, cd);
    precise float dop = fma(a, b, -cd);
    return dop + err;
}

// a * b as p + e exactly (Dekker's product with Veltkamp's splitting): plain multiplies and
// adds, where fma() may not help (lavapipe computes it with two roundings). |a|, |b| < 1e34.
void twoProduct(float a, float b, out float p, out float e) {
    precise float product = a * b;
    precise float sa = 4097.0 * a;
    precise float ah = sa - (sa - a);
    precise float al = a - ah;
    precise float sb = 4097.0 * b;
    precise float bh = sb - (sb - b);
    precise float bl = b - bh;
    precise float error = ((ah * bh - product) + ah * bl + al * bh) + al * bl;
    p = product;
    e = error;
}

// a * b - c * d with its sign exact wherever the two products are close (where they cancel,
// their difference is exact), and zero only when it is.
float exactSignDifferenceOfProducts(float a, float b, float c, float d) {
    float p1, e1, p2, e2;
    twoProduct(a, b, p1, e1);
    twoProduct(c, d, p2, e2);
    precise float r = (p1 - p2) + (e1 - e2);
    return r;
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
bool allFinite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

// Orthonormal basis around a unit vector n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
void buildBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Local shading frame: z is the normal. Directions point away from the surface.
struct Frame {
    vec3 t;
    vec3 b;
    vec3 n;
};
Frame makeFrame(vec3 n) {
    Frame f;
    f.n = n;
    buildBasis(n, f.t, f.b);
    return f;
}
vec3 toLocal(Frame f, vec3 v) { return vec3(dot(v, f.t), dot(v, f.b), dot(v, f.n)); }
vec3 toWorld(Frame f, vec3 v) { return f.t * v.x + f.b * v.y + f.n * v.z; }

#endif
