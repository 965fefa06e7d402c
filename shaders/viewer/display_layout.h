// The viewer's display pass (shaders/viewer/display.comp): its push constants and enums,
// shared by C++ (src/viewer/display_pass.cpp, with a static_assert on the size) and GLSL,
// under the same std430 rules as shaders/shared/layout.h.
#ifndef PT_SHADERS_VIEWER_DISPLAY_LAYOUT_H
#define PT_SHADERS_VIEWER_DISPLAY_LAYOUT_H
#include "shared/layout.h"

#ifdef __cplusplus
namespace pt::gpu {
#endif

// ---- Tone mapping operators (GpuDisplayPush::op) ----
#define DISPLAY_TONEMAP_CLAMP 0u        // clamp to [0, 1], then the transfer curve
#define DISPLAY_TONEMAP_PHOTOGRAPHIC 1u // the course's global Reinhard (src/film/tonemap.cpp)
#define DISPLAY_TONEMAP_ACES 2u         // Narkowicz's 2015 fit of the ACES filmic curve

// ---- Flags ----
#define DISPLAY_FLAG_SRGB 1u // sRGB transfer curve; otherwise C^invGamma
#define DISPLAY_FLAG_BGRA 2u // the swapchain stores B, G, R, A in byte order 0..3

// Tone maps the accumulated sums (film resolution) into the window's pixels (one packed
// 8-bit colour per pixel, in the swapchain format's byte order). A window pixel maps to the
// film pixel under it (nearest), so a reduced-resolution film fills the window. Film pixels
// without any sample yet keep what the display buffer showed before.
struct GpuDisplayPush {
    uint64_t accumulation; // the sums, laid out as GpuSceneParams::accumulation (ACCUM_*)
    uint64_t display;      // uint[window pixels]
    uvec2 filmSize;
    uvec2 windowSize;
    uint spp;         // samples in every film pixel
    uint passSamples; // samples the pass in progress added to its first passTiles tiles
    uint passTiles;
    uint tileSize; // tile side in film pixels, tiles numbered row by row
    uint tilesX;
    uint op;          // DISPLAY_TONEMAP_*
    uint flags;       // DISPLAY_FLAG_*
    float exposure;   // 2^EV
    float toL;        // photographic: key / L_avg, L_avg of the exposed luminance
    float invWhite2;  // photographic: 1 / L_white^2; 0 without burn-out
    float saturation; // photographic
    float invGamma;   // without DISPLAY_FLAG_SRGB
    uint64_t splats;  // light tracing's splat sums (uint64[SPLAT_WORDS_PER_PIXEL * film pixels]), or 0
    float splatScale; // 1 / (SPLAT_SUM_SCALE x samples per pixel so far): splat sum to mean
    uint pad0;
};
PT_CHECK_SIZE(GpuDisplayPush, 96);

#ifdef __cplusplus
} // namespace pt::gpu
#endif
#endif
