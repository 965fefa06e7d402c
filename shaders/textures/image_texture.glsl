// Image textures from the one texel buffer: wrap modes, nearest or bilinear filtering, and the
// sRGB / gamma 2.2 decoding done per texel before filtering (filtering encoded values would
// darken edges).
#ifndef PT_TEXTURES_IMAGE_TEXTURE_GLSL
#define PT_TEXTURES_IMAGE_TEXTURE_GLSL
#include "common/buffers.glsl"

float srgbToLinear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

// One texel, decoded to linear RGBA.
vec4 fetchTexel(GpuTexture tex, int x, int y) {
    uint index = uint(y) * tex.width + uint(x);
    UintRef texels = UintRef(scene.texels);
    if ((tex.flags & TEXTURE_FLAG_FLOAT) != 0u) {
        uint base = tex.texelOffset + 4u * index;
        return vec4(uintBitsToFloat(texels.v[base]), uintBitsToFloat(texels.v[base + 1u]),
            uintBitsToFloat(texels.v[base + 2u]), uintBitsToFloat(texels.v[base + 3u]));
    }
    vec4 c = unpackUnorm4x8(texels.v[tex.texelOffset + index]);
    if ((tex.flags & TEXTURE_FLAG_SRGB) != 0u)
        c.rgb = vec3(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b));
    else if ((tex.flags & TEXTURE_FLAG_GAMMA_22) != 0u)
        c.rgb = pow(c.rgb, vec3(2.2));
    return c;
}

// Non-negative remainder of i by n > 0. Vulkan leaves % undefined for negative operands (NVIDIA's
// driver returns other values than lavapipe), so i is first shifted up by a multiple of n.
int positiveRemainder(int i, int n) {
    if (i < 0) i += n * ((n - 1 - i) / n);
    return i % n;
}

// Integer texel coordinate under a wrap mode (TEXTURE_WRAP_*).
int wrapTexel(int i, int size, uint mode) {
    if (mode == TEXTURE_WRAP_CLAMP) return clamp(i, 0, size - 1);
    if (mode == TEXTURE_WRAP_MIRROR) {
        int period = 2 * size;
        int m = positiveRemainder(i, period);
        return m < size ? m : period - 1 - m;
    }
    return positiveRemainder(i, size);
}

// uv in texture space (0..1 across the image, v = 0 at the top row).
vec4 sampleImage(GpuTexture tex, vec2 uv) {
    uint wrapU = (tex.flags >> TEXTURE_WRAP_U_SHIFT) & 3u;
    uint wrapV = (tex.flags >> TEXTURE_WRAP_V_SHIFT) & 3u;
    ivec2 size = ivec2(tex.width, tex.height);
    // Keep texel coordinates within 2^24: float-to-int conversion is then exact and defined,
    // and positiveRemainder cannot overflow.
    vec2 st = clamp(uv * vec2(size), vec2(-16777216.0), vec2(16777216.0));
    if ((tex.flags & TEXTURE_FLAG_BILINEAR) == 0u) {
        ivec2 i = ivec2(floor(st));
        return fetchTexel(tex, wrapTexel(i.x, size.x, wrapU), wrapTexel(i.y, size.y, wrapV));
    }
    // Texel centres sit at half-integers.
    vec2 f = st - 0.5;
    ivec2 i0 = ivec2(floor(f));
    vec2 w = f - vec2(i0);
    int x0 = wrapTexel(i0.x, size.x, wrapU), x1 = wrapTexel(i0.x + 1, size.x, wrapU);
    int y0 = wrapTexel(i0.y, size.y, wrapV), y1 = wrapTexel(i0.y + 1, size.y, wrapV);
    return mix(mix(fetchTexel(tex, x0, y0), fetchTexel(tex, x1, y0), w.x),
        mix(fetchTexel(tex, x0, y1), fetchTexel(tex, x1, y1), w.x), w.y);
}

#endif
