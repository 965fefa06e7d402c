// What a camera ray that escapes sees when there is no environment: the course's
// replace_background texture across the image window, else the background colour.
#ifndef PT_INTEGRATOR_BACKGROUND_GLSL
#define PT_INTEGRATOR_BACKGROUND_GLSL
#include "common/buffers.glsl"
#include "textures/texture.glsl"

// The texture spans the camera's image window, so the ray's direction gives the film
// position (v = 0 at the top).
vec3 backgroundTexel(vec3 direction) {
    GpuCamera c = scene.camera;
    float z = dot(direction, c.forward);
    vec2 film = vec2(dot(direction, c.right), dot(direction, c.up)) / max(z, 1e-20);
    vec2 uv =
        vec2((film.x - c.window.x) / (c.window.y - c.window.x), (c.window.w - film.y) / (c.window.w - c.window.z));
    return evalTexture(scene.backgroundTexture, uv, direction).rgb;
}

// `cameraRay`: the escaping ray is the camera's own (the texture is only for those).
vec3 backgroundRadiance(vec3 direction, bool cameraRay) {
    if ((HAS_TEXTURES || HAS_PROCEDURAL) && cameraRay && scene.backgroundTexture != NO_TEXTURE)
        return backgroundTexel(direction);
    return scene.background;
}

#endif
