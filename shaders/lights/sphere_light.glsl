// Emissive spheres and ellipsoids. A round sphere seen from outside is sampled uniformly in the
// cone of directions it subtends (pdf 1 / (2 pi (1 - cos theta_max))); an ellipsoid, or a sphere
// emitting inwards, by a uniform point on the unit sphere mapped to world space, whose density
// per world area is 1 / (4 pi J) with J the map's area scale at that point.
#ifndef PT_LIGHTS_SPHERE_LIGHT_GLSL
#define PT_LIGHTS_SPHERE_LIGHT_GLSL
#include "lights/light_common.glsl"
#include "common/math.glsl"
#include "geometry/sphere.glsl"
#include "geometry/motion.glsl"

// Where a moving sphere light has moved at the path's time (motion blur).
vec3 sphereLightOffset(GpuSphere sphere) {
    return (HAS_MOTION && sphere.motion != NO_MOTION) ? motionOffset(sphere.motion) : vec3(0.0);
}

// 1 - cos(theta_max) of the cone a sphere of radius r at distance^2 d2 subtends, without the
// cancellation of 1 - sqrt(1 - sin^2) for small (sun-sized) spheres.
float coneOneMinusCos(float r, float d2) {
    float sin2 = min(r * r / d2, 1.0);
    return sin2 / (1.0 + sqrt(1.0 - sin2));
}

// Area scale J of the unit-sphere map at object-space point po, and the world normal there.
float sphereAreaScale(GpuSphere sphere, GpuLight light, vec3 po, out vec3 normal) {
    vec3 m =
        sphere.worldToObject[0].xyz * po.x + sphere.worldToObject[1].xyz * po.y + sphere.worldToObject[2].xyz * po.z;
    float len = length(m);
    normal = m / len;
    return light.area * len; // light.area holds |det| of the linear map
}

float sphereLightPdf(GpuLight light, vec3 x, vec3 p) {
    GpuSphere sphere = SphereRef(scene.spheres).v[light.primitive];
    vec3 offset = sphereLightOffset(sphere);
    vec3 toCentre = light.position + offset - x;
    float d2 = dot(toCentre, toCentre);
    if (light.radius > 0.0 && d2 > light.radius * light.radius)
        return light.pmf / (TWO_PI * coneOneMinusCos(light.radius, d2));
    vec3 po = normalize(toSphereObject(sphere, p - offset));
    vec3 n;
    float J = sphereAreaScale(sphere, light, po, n);
    vec3 d = p - x;
    float dist2 = dot(d, d);
    float c = abs(dot(n, d)) * inversesqrt(dist2);
    return c > 0.0 ? light.pmf * dist2 / (4.0 * PI * J * c) : 0.0;
}

LightSample sampleSphereLight(GpuLight light, vec3 x, vec2 u) {
    LightSample s = noLightSample();
    GpuSphere sphere = SphereRef(scene.spheres).v[light.primitive];
    GpuMaterial mat = sceneMaterials.v[sphere.materialIndex];
    vec3 offset = sphereLightOffset(sphere);
    vec3 centre = light.position + offset;
    vec3 toCentre = centre - x;
    float d2 = dot(toCentre, toCentre);
    if (light.radius > 0.0 && d2 > light.radius * light.radius) {
        float oneMinusCosMax = coneOneMinusCos(light.radius, d2);
        float oneMinusCos = u.x * oneMinusCosMax;
        float cosTheta = 1.0 - oneMinusCos;
        // sin^2 = (1 - cos)(1 + cos), not 1 - cos^2: for a sun-sized sphere (1 - cos ~ 1e-5)
        // the latter keeps only ~2 significant digits, which moves silhouette samples' points
        // (and their shadow rays' ends) by a good fraction of the radius.
        float sinTheta = sqrt(max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
        float phi = TWO_PI * u.y;
        float dc = sqrt(d2);
        Frame f = makeFrame(toCentre / dc);
        s.wi = toWorld(f, vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta));
        // Distance to the near side along wi (clamped at the silhouette).
        s.distance = dc * cosTheta - sqrt(max(0.0, light.radius * light.radius - d2 * sinTheta * sinTheta));
        s.point = x + s.distance * s.wi;
        s.normal = normalize(s.point - centre);
        s.radiance = emittedRadiance(mat, true);
        s.pdf = light.pmf / (TWO_PI * oneMinusCosMax);
        return s;
    }
    vec3 po = sampleUniformSphere(u);
    s.point = transformPoint(sphere.objectToWorld, po) + offset;
    float J = sphereAreaScale(sphere, light, po, s.normal);
    vec3 d = s.point - x;
    float dist2 = dot(d, d);
    s.distance = sqrt(dist2);
    s.wi = d / s.distance;
    float cosLight = dot(s.normal, -s.wi);
    s.radiance = emittedRadiance(mat, cosLight > 0.0);
    s.pdf = (cosLight != 0.0 && dist2 > 0.0) ? light.pmf * dist2 / (4.0 * PI * J * abs(cosLight)) : 0.0;
    return s;
}

#endif
