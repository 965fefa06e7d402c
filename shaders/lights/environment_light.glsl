// The environment: an equirectangular radiance map (or a constant, stored as a small map),
// importance-sampled by a 2D piecewise-constant distribution over its texels, weighted by
// luminance x sin(theta) so that sampling density matches solid angle (no pole artifacts).
// Mapping (the CENG795 course's): u = (1 + atan2(d.x, -d.z) / pi) / 2, v = acos(d.y) / pi.
#ifndef PT_LIGHTS_ENVIRONMENT_LIGHT_GLSL
#define PT_LIGHTS_ENVIRONMENT_LIGHT_GLSL
#include "lights/light_common.glsl"
#include "common/math.glsl"

// World direction to the map's frame (the map rotates about +y) and back.
vec3 envToLocal(vec3 d) {
    float c = scene.envRotationCos, s = scene.envRotationSin;
    return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}
vec3 envToWorld(vec3 d) {
    float c = scene.envRotationCos, s = scene.envRotationSin;
    return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

vec2 envUv(vec3 local) {
    float u = 0.5 * (1.0 + atan(local.x, -local.z) * INV_PI);
    float v = acos(clamp(local.y, -1.0, 1.0)) * INV_PI;
    return vec2(u, v);
}

vec3 envDirection(vec2 uv) {
    float phi = PI * (2.0 * uv.x - 1.0);
    float theta = PI * uv.y;
    float sinTheta = sin(theta);
    return vec3(sinTheta * sin(phi), cos(theta), -sinTheta * cos(phi));
}

uvec2 envTexel(vec2 uv) {
    uvec2 size = uvec2(scene.envWidth, scene.envHeight);
    return min(uvec2(uv * vec2(size)), size - 1u);
}

vec3 envRadiance(vec3 worldDir) {
    uvec2 t = envTexel(envUv(envToLocal(worldDir)));
    return Vec4Ref(scene.envTexels).v[t.y * scene.envWidth + t.x].rgb;
}

// Probability of texel t under the sampling distribution (the CDF steps), times the texel count:
// the density over [0,1]^2.
float envTexelDensity(uvec2 t) {
    FloatRef marginal = FloatRef(scene.envMarginal);
    FloatRef conditional = FloatRef(scene.envConditional);
    uint row = t.y * (scene.envWidth + 1u);
    float pRow = marginal.v[t.y + 1u] - marginal.v[t.y];
    float pCol = conditional.v[row + t.x + 1u] - conditional.v[row + t.x];
    return pRow * pCol * float(scene.envWidth * scene.envHeight);
}

// Solid-angle pdf of light sampling producing direction worldDir (selection included).
float envPdf(float pmf, vec3 worldDir) {
    vec3 local = envToLocal(worldDir);
    vec2 uv = envUv(local);
    // sin(theta) from x and z, not sqrt(1 - y^2): the latter loses all precision at the poles.
    float sinTheta = length(local.xz) / length(local);
    if (sinTheta <= 0.0) return 0.0;
    return pmf * envTexelDensity(envTexel(uv)) / (2.0 * PI * PI * sinTheta);
}

// Index i with cdf[i] <= u < cdf[i + 1] among n steps starting at cdf[offset].
uint searchCdf(FloatRef cdf, uint offset, uint n, float u) {
    uint lo = 0u, hi = n;
    while (lo + 1u < hi) {
        uint mid = (lo + hi) >> 1u;
        if (cdf.v[offset + mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

LightSample sampleEnvironment(GpuLight light, vec2 u) {
    LightSample s = noLightSample();
    FloatRef marginal = FloatRef(scene.envMarginal);
    FloatRef conditional = FloatRef(scene.envConditional);
    uint y = searchCdf(marginal, 0u, scene.envHeight, u.y);
    uint rowOffset = y * (scene.envWidth + 1u);
    uint x = searchCdf(conditional, rowOffset, scene.envWidth, u.x);
    // Reuse the position of u inside the chosen steps as the position inside the texel.
    float y0 = marginal.v[y], y1 = marginal.v[y + 1u];
    float x0 = conditional.v[rowOffset + x], x1 = conditional.v[rowOffset + x + 1u];
    vec2 inside = vec2((u.x - x0) / max(x1 - x0, 1e-30), (u.y - y0) / max(y1 - y0, 1e-30));
    vec2 uv = (vec2(x, y) + clamp(inside, 0.0, 0.99999994)) / vec2(scene.envWidth, scene.envHeight);
    uv.y = clamp(uv.y, 1e-7, 1.0 - 1e-7); // never exactly on a pole, where the density is singular
    vec3 local = envDirection(uv);
    float sinTheta = length(local.xz);
    if (sinTheta <= 0.0) return s;
    s.wi = envToWorld(local);
    s.distance = FLOAT_MAX;
    // Radiance and pdf of the direction itself, through the same functions escaping BSDF rays
    // use, so a direction rounding onto a neighbouring texel still gets matching MIS weights.
    s.radiance = envRadiance(s.wi);
    s.pdf = envPdf(light.pmf, s.wi);
    return s;
}

#endif
