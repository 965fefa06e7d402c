#pragma once
// Host side of the viewer's tone mapping: the operators it cycles through, the image
// statistics the photographic operator needs on the GPU, and the PNG of what is shown.
#include "image/image.h"
#include "scene/scene.h"

#include <filesystem>

namespace pt::viewer {

enum class DisplayOperator { Srgb, Photographic, Aces };
const char* operatorName(DisplayOperator op);

// The photographic operator's global terms for `mean` at `exposureStops`, computed as
// src/film/tonemap.cpp does: key / L_avg (log-average of the exposed luminance over finite
// pixels) and 1 / L_white^2 from the burn-out percentile (0 without burn-out).
struct PhotographicTerms {
    float toL = 1.0f;
    float invWhite2 = 0.0f;
};
PhotographicTerms photographicTerms(const Image& mean, const TonemapSettings& settings, float exposureStops);

// The settings used for `op` given the scene camera's own (`scene`): sRGB clamps with the sRGB
// curve; Photographic keeps the camera's key, burn, saturation and curve (defaults otherwise).
TonemapSettings settingsFor(DisplayOperator op, const TonemapSettings& scene);

// Narkowicz's ACES fit (as in shaders/viewer/display.comp).
float acesFit(float x);

// Writes what the viewer shows for `op` at `exposureStops` as an 8-bit PNG.
void writeDisplayPng(const std::filesystem::path& path, const Image& mean, DisplayOperator op,
    const TonemapSettings& scene, float exposureStops);

} // namespace pt::viewer
