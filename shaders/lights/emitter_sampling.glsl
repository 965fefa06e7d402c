// Points on emitters for paths that start at the light (the caustic light tracer, and the light
// subpaths of bidirectional path tracing): which random dimensions they draw, and a point on an
// area emitter with its density.
#ifndef PT_LIGHTS_EMITTER_SAMPLING_GLSL
#define PT_LIGHTS_EMITTER_SAMPLING_GLSL
#include "common/math.glsl"
#include "common/sampling.glsl"
#include "geometry/sphere.glsl"
#include "lights/light_common.glsl"
#include "lights/sphere_light.glsl"
#include "lights/triangle_light.glsl"
#include "shared/features.glsl"

// Light paths draw from their own block of dimensions, far from the camera path's, so adding
// them leaves the camera samples (and every image without light tracing) unchanged.
const uint DIM_LIGHT_PATH = 0x40000000u;
const uint DIM_LT_SELECT = 0u; // 1D: which light
const uint DIM_LT_POINT = 1u;  // 2D: point on it
const uint DIM_LT_EMIT = 3u;   // 2D: emitted direction
const uint DIM_LT_SIDE = 5u;   // 1D: side of a double-sided emitter
const uint DIM_LT_FIRST_BOUNCE = 6u;
const uint DIM_LT_LOBE = 0u;      // per bounce, 1D: lobe (reflect or refract)
const uint DIM_LT_DIRECTION = 1u; // 2D: direction at a receiver
const uint DIM_LT_ROULETTE = 3u;
const uint DIMS_PER_LT_BOUNCE = 4u;

uint lightPathDimension(uint offset) { return DIM_LIGHT_PATH + offset; }
uint lightBounceDimension(uint bounce, uint offset) {
    return DIM_LIGHT_PATH + DIM_LT_FIRST_BOUNCE + bounce * DIMS_PER_LT_BOUNCE + offset;
}

// Area emitters light paths start from (the caustic light tracer's, and BDPT's): emissive
// triangles, and spheres without an emission texture (sphere light sampling has none either).
bool isLightTracedEmitter(uint lightIndex) {
    if (lightIndex == NO_LIGHT) return false;
    GpuLight light = sceneLights.v[lightIndex];
    if (light.type == LIGHT_TRIANGLE) return true;
    if (!HAS_SPHERES || light.type != LIGHT_SPHERE) return false;
    GpuSphere sphere = SphereRef(scene.spheres).v[light.primitive];
    return sceneMaterials.v[sphere.materialIndex].emissiveTexture == NO_TEXTURE;
}

// A point emitting light, with its area density (selection included).
struct EmitterPoint {
    vec3 p;
    vec3 ng; // geometric normal: the front (emitting) side
    vec3 Le;
    float magnitude;
    uint materialIndex;
    float pdf; // per unit area, times the light's selection probability
    bool valid;
};

EmitterPoint sampleEmitterPoint(uint lightIndex, vec2 u) {
    EmitterPoint e;
    e.valid = false;
    GpuLight light = sceneLights.v[lightIndex];
    if (!isLightTracedEmitter(lightIndex) || light.pmf <= 0.0) return e;
    if (light.type == LIGHT_TRIANGLE) {
        GpuTriangle tri = placedTriangle(loadTriangle(light.primitive)); // where it is at the path's time
        vec2 b = sampleUniformTriangle(u);
        e.p = (1.0 - b.x - b.y) * tri.p0 + b.x * tri.p1 + b.y * tri.p2;
        e.ng = normalize(cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
        e.magnitude = maxComponent(max(max(abs(tri.p0), abs(tri.p1)), abs(tri.p2)));
        e.materialIndex = tri.materialIndex;
        e.pdf = light.pmf / light.area;
        e.Le = triangleEmission(light.primitive, sceneMaterials.v[tri.materialIndex], b, e.p, true);
    } else {
        // A uniform point on the unit sphere mapped to world space: density 1 / (4 pi J).
        GpuSphere sphere = SphereRef(scene.spheres).v[light.primitive];
        vec3 po = sampleUniformSphere(u);
        vec3 offset = sphereLightOffset(sphere);
        e.p = transformPoint(sphere.objectToWorld, po) + offset;
        float J = sphereAreaScale(sphere, light, po, e.ng);
        e.magnitude = sphereMagnitude(sphere, offset);
        e.materialIndex = sphere.materialIndex;
        e.pdf = light.pmf / (4.0 * PI * J);
        e.Le = sceneMaterials.v[sphere.materialIndex].emission;
    }
    e.valid = e.pdf > 0.0 && maxComponent(e.Le) > 0.0 && allFinite(e.p) && allFinite(e.ng);
    return e;
}

#endif
