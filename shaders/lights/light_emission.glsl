// Light leaving a light, for the light subpaths of bidirectional path tracing: a point and a
// direction sampled together, and the densities MIS needs of any point and direction a camera
// path or a connection produced. Area emitters (triangles, spheres, the course's squares) emit
// cosine-weighted from their lit side (either side of a double-sided one, picked with
// probability 1/2); point lights uniformly over the sphere, spots uniformly over their cone.
// Lights at infinity (the environment, directional lights) send parallel light in a direction:
// the environment's sampled as light sampling samples it, a directional light's its own; the
// path starts on a disc across that direction, of the scene sphere's radius, outside the scene
// (pbrt's and SmallVCM's construction). Their emission density is per unit disc area and solid
// angle; the first segment's length does not enter the MIS sums (integrator/bdpt.glsl).
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
    bool hittable;   // a camera path can hit it (emissive triangles and spheres, the environment)
    bool infinite;   // the environment or a directional light: p is on the disc outside the scene
    bool valid;
};

// Density per unit area of the disc the paths of a light at infinity start on.
float infiniteLightDiscPdf() { return 1.0 / (PI * scene.sceneSphere.w * scene.sceneSphere.w); }

// Light from a light at infinity: direction toLight (unit, towards the light), radiance Le (a
// directional light's irradiance), direction density pdfDirection (selection included; a
// directional light's: its selection pmf, the delta left out as light sampling leaves it out).
LightEmission infiniteLightEmission(vec3 toLight, vec3 Le, float pdfDirection, vec2 uPoint) {
    LightEmission em;
    vec3 t, b;
    buildBasis(toLight, t, b);
    vec2 disc = sampleConcentricDisk(uPoint) * scene.sceneSphere.w;
    em.p = scene.sceneSphere.xyz + scene.sceneSphere.w * toLight + disc.x * t + disc.y * b;
    em.normal = -toLight;
    em.direction = -toLight;
    em.magnitude = 0.0;
    em.cosLight = 1.0;
    em.pdfEmit = pdfDirection * infiniteLightDiscPdf();
    em.beta = Le / em.pdfEmit;
    em.hittable = false;
    em.infinite = true;
    em.valid = pdfDirection > 0.0 && maxComponent(em.beta) > 0.0 && allFinite(em.beta) && allFinite(em.p);
    return em;
}

bool isPositionDeltaLight(GpuLight light) {
    return HAS_PUNCTUAL_LIGHTS && (light.type == LIGHT_POINT || light.type == LIGHT_SPOT);
}

// 1 / solid angle of a spot's cone: its directions are sampled uniformly inside it.
float spotConePdf(GpuLight light) { return 1.0 / (TWO_PI * max(1.0 - light.cosCoverage, 1e-7)); }

LightEmission sampleLightEmission(uint lightIndex, vec2 uPoint, vec2 uDirection, float uSide) {
    LightEmission em;
    em.valid = false;
    em.hittable = false;
    em.infinite = false;
    em.normal = vec3(0.0);
    em.magnitude = 0.0;
    GpuLight light = sceneLights.v[lightIndex];
    if (!(light.pmf > 0.0)) return em;
    if (HAS_ENVIRONMENT && light.type == LIGHT_ENVIRONMENT) {
        LightSample ls = sampleEnvironment(light, uDirection);
        if (!(ls.pdf > 0.0)) return em;
        em = infiniteLightEmission(ls.wi, ls.radiance, ls.pdf, uPoint);
        em.hittable = true;
        return em;
    }
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_DIRECTIONAL)
        return infiniteLightEmission(-light.direction, light.intensity, light.pmf, uPoint);
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
// that point and direction; 0 for lights no light subpath starts from. Lights at infinity: any
// p (the disc covers the scene), w the direction the light travels.
float emissionPdf(uint lightIndex, vec3 p, vec3 n, vec3 w) {
    GpuLight light = sceneLights.v[lightIndex];
    if (HAS_ENVIRONMENT && light.type == LIGHT_ENVIRONMENT) return envPdf(light.pmf, -w) * infiniteLightDiscPdf();
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_DIRECTIONAL) return light.pmf * infiniteLightDiscPdf();
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
        float J =
            sphereAreaScale(sphere, light, normalize(toSphereObject(sphere, p - sphereLightOffset(sphere))), normal);
        pdfArea = light.pmf / (4.0 * PI * J);
        materialIndex = sphere.materialIndex;
    }
    float sides = (sceneMaterials.v[materialIndex].flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u ? 2.0 : 1.0;
    return pdfArea * cosLight / (PI * sides);
}

// The density per unit solid angle with which light sampling picks the light at infinity
// lightIndex in direction -w (w the direction its light travels); 0 without light sampling.
float directLightPdfInfinite(uint lightIndex, vec3 w) {
    if (!USE_NEE) return 0.0;
    GpuLight light = sceneLights.v[lightIndex];
    return HAS_ENVIRONMENT && light.type == LIGHT_ENVIRONMENT ? envPdf(light.pmf, -w) : light.pmf;
}

// The density per unit area (per unit "point" for point lights) with which light sampling from
// x (geometric normal xNormal, for the light tree) picks point p (normal n) of light lightIndex;
// 0 without light sampling.
float directLightPdfArea(uint lightIndex, vec3 x, vec3 xNormal, vec3 p, vec3 n) {
    if (!USE_NEE) return 0.0;
    GpuLight light = sceneLights.v[lightIndex];
    light.pmf = lightSelectionPmf(lightIndex, light, x, xNormal);
    if (isPositionDeltaLight(light)) return light.pmf;
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SQUARE) return light.pmf / light.area;
    vec3 d = p - x;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0)) return 0.0;
    float dist = sqrt(dist2);
    vec3 w = d / dist;
    return lightPdfOf(light, x, p, n, dist, w) * abs(dot(n, w)) / dist2;
}

#endif
