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

// Where a pinhole camera sees world point p, for paths that reach the camera from a surface
// (light tracing, bidirectional connections).
struct CameraView {
    uvec2 pixel;
    vec3 wCamera;   // unit, from p towards the camera
    float distance; // from p to the camera
    // 1 / (windowArea d^2 cos^3 theta_c). A pixel's estimate is 1 / A_pixel times the radiance
    // over its image-plane area at unit distance; per unit area of a surface at p that plane area
    // is |wCamera.n| / (d^2 cos^3 theta_c), and divided by the pixel count (one light path per
    // pixel) A_pixel becomes the whole window's area. So importance |wCamera.n| is the camera's
    // density of p per unit area over the pixel count, the weight of a splat and of its MIS.
    float importance;
};

// False where p is behind the camera or outside its window (the inverse of cameraRay).
bool viewFromPinhole(GpuCamera cam, uvec2 imageSize, vec3 p, out CameraView view) {
    vec3 toCamera = cam.origin - p;
    float dist2 = dot(toCamera, toCamera);
    if (!(dist2 > 0.0)) return false;
    view.distance = sqrt(dist2);
    view.wCamera = toCamera / view.distance;
    vec3 v = -toCamera;
    float z = dot(v, cam.forward);
    if (!(z > 0.0)) return false;
    vec2 plane = vec2(dot(v, cam.right), dot(v, cam.up)) / z;
    vec2 f = vec2((plane.x - cam.window.x) / (cam.window.y - cam.window.x),
        (cam.window.w - plane.y) / (cam.window.w - cam.window.z));
    if (!(f.x >= 0.0 && f.x < 1.0 && f.y >= 0.0 && f.y < 1.0)) return false;
    view.pixel = min(uvec2(f * vec2(imageSize)), imageSize - 1u);
    float cosCamera = z / view.distance;
    float windowArea = (cam.window.y - cam.window.x) * (cam.window.w - cam.window.z);
    view.importance = 1.0 / (windowArea * dist2 * cosCamera * cosCamera * cosCamera);
    return true;
}

// The camera's side of a camera path's first vertex, for MIS with light tracing: the pixel count
// over the camera's solid-angle density of direction d, windowArea cos^3 theta_c.
float cameraDirectionWeight(GpuCamera cam, vec3 d) {
    float cosCamera = dot(d, cam.forward);
    float windowArea = (cam.window.y - cam.window.x) * (cam.window.w - cam.window.z);
    return windowArea * cosCamera * cosCamera * cosCamera;
}

#endif
