// Light leaving a light, for the light subpaths of bidirectional path tracing: a point and a
// direction sampled together, and the densities MIS needs of any point and direction a camera
// path or a connection produced. Area emitters (triangles, spheres, the course's squares) emit
// cosine-weighted from their lit side (either side of a double-sided one, picked with
// probability 1/2); point lights uniformly over the sphere, spots uniformly over their cone.
// Directional lights and the environment start no light subpaths: their paths are left to the
// camera-side strategies (hitting them, sampling them), and their emission density is 0.
#ifndef PT_LIGHTS_LIGHT_EMISSION_GLSL
#define PT_LIGHTS_LIGHT_EMISSION_GLSL
#include "lights/emitter_sampling.glsl"
#include "lights/light_sampling.glsl"
#include "lights/punctual_light.glsl"

struct LightEmission {
    vec3 p;          // on the light (point and spot lights: their position)
    vec3 normal;     // area lights: the normal on the side it emits to (0 for point lights)
    vec3 direction;  // unit, leaving the light
    vec3 beta;       // Le |cos| over the density of point and direction (selection included)
    float magnitude; // scales the ray offset of an area light's point
    float cosLight;  // |cos| between normal and direction (1 for point lights)
    float pdfEmit;   // selection x area density x direction density (point lights: no area)
    bool hittable;   // a camera path can hit it (emissive triangles and spheres)
    bool valid;
};

bool isPositionDeltaLight(GpuLight light) {
    return HAS_PUNCTUAL_LIGHTS && (light.type == LIGHT_POINT || light.type == LIGHT_SPOT);
}

// 1 / solid angle of a spot's cone: its directions are sampled uniformly inside it.
float spotConePdf(GpuLight light) { return 1.0 / (TWO_PI * max(1.0 - light.cosCoverage, 1e-7)); }

LightEmission sampleLightEmission(uint lightIndex, vec2 uPoint, vec2 uDirection, float uSide) {
    LightEmission em;
    em.valid = false;
    em.hittable = false;
    em.normal = vec3(0.0);
    em.magnitude = 0.0;
    GpuLight light = sceneLights.v[lightIndex];
    if (!(light.pmf > 0.0)) return em;
    if (isPositionDeltaLight(light)) {
        em.p = light.position;
        em.cosLight = 1.0;
        vec3 I = light.intensity;
        float pdfDirection;
        if (light.type == LIGHT_POINT) {
            em.direction = sampleUniformSphere(uDirection);
            pdfDirection = 1.0 / (4.0 * PI);
        } else {
            float cosTheta = mix(1.0, light.cosCoverage, uDirection.x);
            float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
            float phi = TWO_PI * uDirection.y;
            em.direction =
                toWorld(makeFrame(light.direction), vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta));
            pdfDirection = spotConePdf(light);
            I *= spotFalloff(light, cosTheta);
        }
        em.pdfEmit = light.pmf * pdfDirection;
        em.beta = I / em.pdfEmit;
        em.valid = maxComponent(em.beta) > 0.0 && allFinite(em.beta);
        return em;
    }
    vec3 Le;
    float pdfArea; // selection included
    float sides = 2.0;
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SQUARE) {
        vec3 t, b;
        buildBasis(light.direction, t, b);
        em.p = light.position + light.radius * ((uPoint.x - 0.5) * t + (uPoint.y - 0.5) * b);
        em.normal = light.direction;
        em.magnitude = max(maxComponent(abs(light.position)), light.radius);
        Le = light.intensity;
        pdfArea = light.pmf / light.area;
    } else {
        EmitterPoint e = sampleEmitterPoint(lightIndex, uPoint);
        if (!e.valid) return em;
        em.p = e.p;
        em.normal = e.ng;
        em.magnitude = e.magnitude;
        em.hittable = true;
        Le = e.Le;
        pdfArea = e.pdf;
        if ((sceneMaterials.v[e.materialIndex].flags & MATERIAL_FLAG_DOUBLE_SIDED) == 0u) sides = 1.0;
    }
    if (sides == 2.0 && uSide < 0.5) em.normal = -em.normal;
    vec3 local = sampleCosineHemisphere(uDirection);
    if (local.z <= 0.0) return em;
    em.direction = toWorld(makeFrame(em.normal), local);
    em.cosLight = local.z;
    em.pdfEmit = pdfArea * local.z / (PI * sides);
    em.beta = Le * (PI * sides / pdfArea); // Le cos / (pdfArea cos / (pi sides))
    em.valid = pdfArea > 0.0 && maxComponent(em.beta) > 0.0 && allFinite(em.beta) && allFinite(em.p);
    return em;
}

// The density with which a light subpath starts at point p of light lightIndex (normal n there,
// either way round) and leaves in direction w (unit): what sampleLightEmission's pdfEmit is for
// that point and direction; 0 for lights no light subpath starts from.
float emissionPdf(uint lightIndex, vec3 p, vec3 n, vec3 w) {
    GpuLight light = sceneLights.v[lightIndex];
    if (isPositionDeltaLight(light)) {
        if (light.type == LIGHT_POINT) return light.pmf / (4.0 * PI);
        return dot(w, light.direction) >= light.cosCoverage ? light.pmf * spotConePdf(light) : 0.0;
    }
    float cosLight = abs(dot(n, w));
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SQUARE) return light.pmf / light.area * cosLight / TWO_PI;
    if (!isLightTracedEmitter(lightIndex)) return 0.0;
    float pdfArea;
    uint materialIndex;
    if (light.type == LIGHT_TRIANGLE) {
        pdfArea = light.pmf / light.area;
        materialIndex = loadTriangle(light.primitive).materialIndex;
    } else {
        GpuSphere sphere = SphereRef(scene.spheres).v[light.primitive];
        vec3 normal;
        float J = sphereAreaScale(sphere, light, normalize(toSphereObject(sphere, p)), normal);
        pdfArea = light.pmf / (4.0 * PI * J);
        materialIndex = sphere.materialIndex;
    }
    float sides = (sceneMaterials.v[materialIndex].flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u ? 2.0 : 1.0;
    return pdfArea * cosLight / (PI * sides);
}

// The density per unit area (per unit "point" for point lights) with which light sampling from
// x picks point p (normal n) of light lightIndex; 0 without light sampling.
float directLightPdfArea(uint lightIndex, vec3 x, vec3 p, vec3 n) {
    if (!USE_NEE) return 0.0;
    GpuLight light = sceneLights.v[lightIndex];
    if (isPositionDeltaLight(light)) return light.pmf;
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SQUARE) return light.pmf / light.area;
    vec3 d = p - x;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0)) return 0.0;
    float dist = sqrt(dist2);
    vec3 w = d / dist;
    return lightPdf(lightIndex, x, p, n, dist, w) * abs(dot(n, w)) / dist2;
}

#endif
