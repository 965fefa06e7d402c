#ifndef PT_INTEGRATOR_CAMERA_GLSL
#define PT_INTEGRATOR_CAMERA_GLSL
#include "common/buffers.glsl"
#include "geometry/ray.glsl"

// Pinhole camera ray through image position (x, y) in pixels, y down from the top row.
Ray cameraRay(GpuCamera cam, vec2 imagePos, uvec2 imageSize) {
    vec2 ndc = imagePos / vec2(imageSize) * 2.0 - 1.0;
    vec3 d = cam.forward + (ndc.x * cam.tanHalfFovY * cam.aspect) * cam.right - (ndc.y * cam.tanHalfFovY) * cam.up;
    Ray r;
    r.origin = cam.origin;
    r.direction = normalize(d);
    return r;
}

#endif
