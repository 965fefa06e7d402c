// Evaluating any texture (image or course procedural) at a surface point.
#ifndef PT_TEXTURES_TEXTURE_GLSL
#define PT_TEXTURES_TEXTURE_GLSL
#include "common/buffers.glsl"
#include "shared/features.glsl"
#include "textures/image_texture.glsl"
#include "textures/perlin.glsl"

GpuTexture loadTexture(uint index) { return TextureRef(scene.textures).v[index]; }

// The course checkerboard: x = int((p.x + offset) * scale) % 2 per axis, black where
// (x xor y) != z. Truncation as the course's C++ wrote it; its signed remainder is non-zero
// exactly for odd values, which the low bit tells (Vulkan leaves % of negatives undefined).
vec3 checkerboard(GpuTexture tex, vec3 p) {
    ivec3 c = ivec3((p + tex.patternOffset) * tex.patternScale) & 1;
    bvec3 odd = notEqual(c, ivec3(0));
    return (odd.x != odd.y) != odd.z ? tex.colorA : tex.colorB;
}

float perlinValue(GpuTexture tex, vec3 p) {
    float n = perlinNoise(p * tex.patternScale);
    return (tex.flags & TEXTURE_FLAG_PERLIN_ABS) != 0u ? abs(n) : 0.5 * (n + 1.0);
}

// RGBA of texture `tex` at texture coordinates uv and world point p.
vec4 evalTexture(GpuTexture tex, vec2 uv, vec3 p) {
    vec4 value = vec4(1.0);
    if (HAS_PROCEDURAL && tex.type == TEXTURE_CHECKERBOARD) {
        value.rgb = checkerboard(tex, p);
    } else if (HAS_PROCEDURAL && tex.type == TEXTURE_PERLIN) {
        value.rgb = vec3(perlinValue(tex, p));
    } else if (HAS_TEXTURES) {
        vec2 st = vec2(dot(tex.uvRow0.xy, uv) + tex.uvRow0.z, dot(tex.uvRow1.xy, uv) + tex.uvRow1.z);
        value = sampleImage(tex, st);
    }
    value.rgb *= tex.valueScale;
    return value;
}

vec4 evalTexture(uint index, vec2 uv, vec3 p) { return evalTexture(loadTexture(index), uv, p); }

#endif
