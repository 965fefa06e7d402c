#pragma once
// Display mapping for the PNG output (the EXR stays linear): the CENG795 course's tone
// mapping pipeline (docs/ceng795-format.md section 9) plus a plain clamp, both ending in 8-bit RGB.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "image/image.h"
#include "scene/scene.h"

namespace pt {

// Rec. 709 / sRGB luminance weights, as the course specifies.
inline constexpr double kTonemapLumR = 0.2126;
inline constexpr double kTonemapLumG = 0.7152;
inline constexpr double kTonemapLumB = 0.0722;

// The delta in the log-average luminance L_avg = exp(mean(log(delta + Y))). It exists so that
// black pixels (background, shadow) contribute log(delta) instead of -infinity, and it matters
// exactly when an image has many: the CENG795 course's official direct-lighting images (7.8%
// black pixels in the shadows) are reproduced from their EXRs to 0.45 of an 8-bit level with
// 1e-6, and are 13 levels off with the 1e-4 often quoted with Reinhard et al. 2002 (6 with
// 1e-5, 7 with 1e-7). Images without black pixels do not notice the difference.
inline constexpr double kTonemapLogDelta = 1e-6;

// Maps a linear image to 8-bit RGB: 3 bytes per pixel, row-major, top row first; alpha is
// ignored. The image is first multiplied by 2^exposureStops, then:
//  - Clamp: each channel clamped to [0,1] (key, burnPercent and saturation are unused).
//    With srgb this is byte-for-byte what writePng produces.
//  - Photographic: global Reinhard. Negative channels are clamped to 0 first (they have
//    no physical meaning, e.g. reconstruction-filter ringing). Y = 0.2126R + 0.7152G +
//    0.0722B, L = key*Y/L_avg. burnPercent = 0: Ld = L/(1+L). burnPercent > 0: L_white is
//    the L of the pixel at the (100 - burn) percentile, i.e. index floor(n(1 - burn/100))
//    of the ascending luminances, so the brightest ceil(n*burn/100) pixels reach 1.0, and
//    Ld = L(1 + L/L_white^2)/(1+L). Colour: C_o = Ld * (C/Y)^saturation; Y = 0 stays black.
//    Note that the key mapping is scale-invariant, so exposure only matters through delta.
// Then every channel is clamped to [0,1] and encoded with the sRGB curve (srgb) or
// C^(1/gamma), and rounded. Pixels with a non-finite R, G or B become magenta
// (255,0,255) and are left out of L_avg and of the percentile, so they do not change the
// other pixels. A 0x0 image gives an empty vector.
// Throws std::invalid_argument for an inconsistent image (negative size, buffer size not
// width*height*4) or unusable settings: exposure not finite or 2^exposure overflowing a
// float; gamma not finite or <= 0 (unless srgb); for Photographic, key not finite or <= 0,
// burnPercent outside [0,100], saturation not finite or < 0.
std::vector<uint8_t> tonemapToRgb8(const Image& image, const TonemapSettings& settings, float exposureStops = 0.0f);

// tonemapToRgb8 written as an 8-bit RGB PNG via a temporary file in the same directory and
// a rename, so readers never see a half-written file and a failure leaves any previous
// file untouched. Throws std::runtime_error("<path>: <problem>") on any failure, including
// an empty image and the argument errors above.
void writeTonemappedPng(
    const std::filesystem::path& path, const Image& image, const TonemapSettings& settings, float exposureStops = 0.0f);

// Display-referred preview: multiplies by 2^exposureStops, clamps to [0,1], applies the
// piecewise sRGB OETF and writes 8-bit RGB (alpha dropped): writeTonemappedPng with the
// default (Clamp, sRGB) settings. Pixels with any non-finite R,G,B become magenta (255,0,255)
// so NaN/Inf bugs are visible. Throws std::runtime_error("<path>: <problem>").
void writePng(const std::filesystem::path& path, const Image& image, float exposureStops = 0.0f);

} // namespace pt
