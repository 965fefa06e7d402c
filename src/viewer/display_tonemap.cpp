#include "viewer/display_tonemap.h"

#include "film/tonemap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pt::viewer {

const char* operatorName(DisplayOperator op) {
    switch (op) {
    case DisplayOperator::Photographic: return "photographic";
    case DisplayOperator::Aces: return "aces";
    default: return "srgb";
    }
}

TonemapSettings settingsFor(DisplayOperator op, const TonemapSettings& scene) {
    TonemapSettings s = scene;
    if (op == DisplayOperator::Photographic) {
        if (scene.op != TonemapSettings::Operator::Photographic) s = TonemapSettings{};
        s.op = TonemapSettings::Operator::Photographic;
        return s;
    }
    s = TonemapSettings{};
    s.op = TonemapSettings::Operator::Clamp;
    s.srgb = true;
    return s;
}

PhotographicTerms photographicTerms(const Image& mean, const TonemapSettings& s, float exposureStops) {
    const double scale = std::exp2(double(exposureStops));
    double logSum = 0.0;
    std::vector<double> lums;
    const size_t n = size_t(mean.width) * mean.height;
    lums.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        const float* p = mean.rgba.data() + 4 * i;
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
        const double y = scale * (kTonemapLumR * std::max(0.0f, p[0]) + kTonemapLumG * std::max(0.0f, p[1]) +
                                     kTonemapLumB * std::max(0.0f, p[2]));
        logSum += std::log(kTonemapLogDelta + y);
        lums.push_back(y);
    }
    PhotographicTerms t;
    if (lums.empty()) return t;
    const double toL = double(s.key) / std::exp(logSum / double(lums.size()));
    t.toL = static_cast<float>(toL);
    if (s.burnPercent > 0.0f) {
        const double exact = double(lums.size()) * double(s.burnPercent) / 100.0;
        const double burned = std::clamp(std::ceil(exact * (1.0 - 1e-7)), 1.0, double(lums.size()));
        const size_t idx = lums.size() - static_cast<size_t>(burned);
        std::nth_element(lums.begin(), lums.begin() + std::ptrdiff_t(idx), lums.end());
        const double white = toL * lums[idx];
        t.invWhite2 = white > 0.0 ? static_cast<float>(std::min(1.0 / (white * white), 1e30)) : 1e30f;
    }
    return t;
}

float acesFit(float x) {
    x = std::max(x, 0.0f);
    return (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
}

void writeDisplayPng(const std::filesystem::path& path, const Image& mean, DisplayOperator op,
    const TonemapSettings& scene, float exposureStops) {
    if (op != DisplayOperator::Aces) {
        writeTonemappedPng(path, mean, settingsFor(op, scene), exposureStops);
        return;
    }
    // ACES: apply the curve here, then clamp and encode with the sRGB curve.
    Image mapped = mean;
    const float scale = std::exp2(exposureStops);
    for (size_t i = 0; i < mapped.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c)
            if (std::isfinite(mapped.rgba[i + c])) mapped.rgba[i + c] = acesFit(scale * mapped.rgba[i + c]);
    writeTonemappedPng(path, mapped, settingsFor(DisplayOperator::Srgb, scene), 0.0f);
}

} // namespace pt::viewer
