// The shadow ray of a light sample, shared by the path tracer's and the classic integrator's
// light sampling: from the offset surface point to the (offset) light point, or to infinity
// for directional lights.
#ifndef PT_INTEGRATOR_SHADOW_RAY_GLSL
#define PT_INTEGRATOR_SHADOW_RAY_GLSL
#include "common/ray_offset.glsl"
#include "geometry/interaction.glsl"
#include "geometry/traverse.glsl"
#include "lights/light_common.glsl"
#include "integrator/ray_counts.glsl"
#include "integrator/camera.glsl"

// Shadow rays stop this fraction short of the (offset) light point, the receiver's own offset
// having already moved the origin off its surface.
const float SHADOW_RAY_FAR = 0.9999;

// True when something lies between the surface point and the light sample.
bool lightOccluded(SurfaceInteraction si, LightSample ls) {
    countShadowRay();
    Ray shadow;
    // Towards the side the surface's normal faces, from the smooth surface (Hanika's
    // shadow-terminator offset, shaders/common/ray_offset.glsl).
    shadow.origin = spawnOrigin(dot(ls.wi, si.nSurface) > 0.0 ? si.pSmooth : si.p, si.ng, ls.wi, si.magnitude);
    float tMax = SHADOW_RAY_FAR;
    if (ls.distance == FLOAT_MAX) {
        shadow.direction = ls.wi; // directional light: unoccluded to infinity
        tMax = FLOAT_MAX;
    } else {
        // Offset the light end too (surfaces only), then stop just short of it.
        // (Lights no ray can hit have nothing to offset from.) The light's size is not at hand,
        // so the offset is the unit-size one: at worst the ray stops 1/65536 short of a tiny light.
        vec3 target = ls.isDelta ? ls.point
                                 : offsetRayOrigin(ls.point, dot(ls.normal, ls.wi) < 0.0 ? ls.normal : -ls.normal, 1.0);
        shadow.direction = target - shadow.origin;
    }
    return traceAny(shadow, tMax);
}

// True when something lies between surface point si and the camera at view (a pinhole).
bool cameraOccluded(SurfaceInteraction si, CameraView view) {
    countShadowRay();
    Ray shadow;
    shadow.origin =
        spawnOrigin(dot(view.wCamera, si.nSurface) > 0.0 ? si.pSmooth : si.p, si.ng, view.wCamera, si.magnitude);
    shadow.direction = scene.camera.origin - shadow.origin;
    return traceAny(shadow, SHADOW_RAY_FAR);
}

#endif
