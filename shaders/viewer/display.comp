#version 460
// The viewer's display pass: tone maps the accumulated sums into the window's pixels
// (see GpuDisplayPush in display_layout.h); the host then copies them to the swapchain image.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "viewer/display_layout.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SumsRef { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer PixelsRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer SplatsRef { uint64_t v[]; };

layout(push_constant) uniform PushBlock { GpuDisplayPush push; };

const vec3 LUMINANCE = vec3(0.2126, 0.7152, 0.0722);

// The piecewise sRGB curve (IEC 61966-2-1), as src/film/tonemap.cpp writes it.
float srgbOetf(float v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055; }

vec3 encode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    if ((push.flags & DISPLAY_FLAG_SRGB) != 0u) return vec3(srgbOetf(c.r), srgbOetf(c.g), srgbOetf(c.b));
    return push.invGamma == 1.0 ? c : pow(c, vec3(push.invGamma));
}

// Global Reinhard with optional burn-out and saturation, as tonemap.cpp's photographicOperator.
vec3 photographic(vec3 c) {
    c = max(c, vec3(0.0));
    float y = dot(c, LUMINANCE);
    if (y <= 0.0) return vec3(0.0);
    float l = push.toL * push.exposure * y;
    float ld = push.invWhite2 > 0.0 ? l * (1.0 + l * push.invWhite2) / (1.0 + l) : l / (1.0 + l);
    vec3 ratio = c / y;
    return ld * (push.saturation == 1.0 ? ratio : pow(ratio, vec3(push.saturation)));
}

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES RRT + ODT.
vec3 acesFit(vec3 x) {
    x = max(x, vec3(0.0));
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, push.windowSize))) return;
    uvec2 film = min(pixel * push.filmSize / push.windowSize, push.filmSize - 1u);
    uvec2 tile = film / push.tileSize;
    uint n = push.spp + (tile.y * push.tilesX + tile.x < push.passTiles ? push.passSamples : 0u);
    if (n == 0u) return; // nothing rendered here yet: keep the previous picture
    // The sum is a double-float (hi + lo, shared/layout.h); lo matters only past ~1e4 samples.
    uint base = ACCUMULATION_VEC4S_PER_PIXEL * (film.y * push.filmSize.x + film.x);
    SumsRef sums = SumsRef(push.accumulation);
    vec3 mean = (sums.v[base + ACCUM_SUM].rgb + sums.v[base + ACCUM_SUM_LO].rgb) / float(n);
    if (push.splats != 0ul) {
        uint splatBase = SPLAT_WORDS_PER_PIXEL * (film.y * push.filmSize.x + film.x) + SPLAT_SUM;
        SplatsRef splats = SplatsRef(push.splats);
        mean += vec3(float(splats.v[splatBase]), float(splats.v[splatBase + 1u]), float(splats.v[splatBase + 2u])) *
                push.splatScale;
    }
    vec3 c;
    if (any(isnan(mean)) || any(isinf(mean))) {
        c = vec3(1.0, 0.0, 1.0); // magenta, as in the PNG
    } else {
        if (push.op == DISPLAY_TONEMAP_PHOTOGRAPHIC)
            c = photographic(mean);
        else if (push.op == DISPLAY_TONEMAP_ACES)
            c = acesFit(push.exposure * mean);
        else
            c = push.exposure * mean;
        c = encode(c);
    }
    uvec3 b = uvec3(round(clamp(c, 0.0, 1.0) * 255.0));
    if ((push.flags & DISPLAY_FLAG_BGRA) != 0u) b = b.bgr;
    PixelsRef(push.display).v[pixel.y * push.windowSize.x + pixel.x] = b.x | (b.y << 8u) | (b.z << 16u) | (255u << 24u);
}
