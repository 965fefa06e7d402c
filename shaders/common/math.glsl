// Constants and small helpers shared by every shader file.
#ifndef PT_COMMON_MATH_GLSL
#define PT_COMMON_MATH_GLSL

const float PI = 3.14159265358979323846;
const float INV_PI = 0.31830988618379067154;
const float TWO_PI = 6.28318530717958647692;
const float FLOAT_MAX = 3.402823466e+38;

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }
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
