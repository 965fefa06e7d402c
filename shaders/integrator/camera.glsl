#ifndef PT_INTEGRATOR_CAMERA_GLSL
#define PT_INTEGRATOR_CAMERA_GLSL
#include "common/buffers.glsl"
#include "common/sampling.glsl"
#include "common/ray.glsl"

// Camera ray through image position (x, y) in pixels, y down from the top row. The image
// plane window (l, r, b, t) at unit distance allows off-centre frusta (the course's NearPlane);
// a thin lens of radius lensRadius focuses at focusDistance along the view direction.
Ray cameraRay(GpuCamera cam, vec2 imagePos, uvec2 imageSize, vec2 uLens) {
    vec2 f = imagePos / vec2(imageSize);
    float x = mix(cam.window.x, cam.window.y, f.x);
    float y = mix(cam.window.w, cam.window.z, f.y);
    vec3 d = cam.forward + x * cam.right + y * cam.up; // forward component 1
    Ray r;
    r.origin = cam.origin;
    r.direction = normalize(d);
    if (cam.lensRadius > 0.0) {
        vec2 lens = cam.lensRadius * sampleConcentricDisk(uLens);
        vec3 lensPoint = cam.origin + lens.x * cam.right + lens.y * cam.up;
        vec3 focusPoint = cam.origin + cam.focusDistance * d;
        r.origin = lensPoint;
        r.direction = normalize(focusPoint - lensPoint);
    }
    return r;
}

#endif
