#include "film/tonemap.h"

#include "image/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace pt {
namespace {

std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// The reason the arguments cannot be tone mapped, or "" when they can. Shared by both
// entry points so each can wrap it in its own exception type (with or without the path).
std::string argumentProblem(const Image& image, const TonemapSettings& s, float exposureStops) {
    if (image.width < 0 || image.height < 0)
        return "invalid image size " + std::to_string(image.width) + "x" + std::to_string(image.height);
    const std::size_t expected = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4;
    if (image.rgba.size() != expected)
        return "pixel buffer holds " + std::to_string(image.rgba.size()) + " floats, expected " +
               std::to_string(expected) + " for " + std::to_string(image.width) + "x" + std::to_string(image.height) +
               " RGBA";
    // Same limit as writePng: the float scale factor must exist. This also keeps every
    // scaled value far inside double range in the photographic path.
    if (!std::isfinite(exposureStops) || !std::isfinite(std::exp2(exposureStops)))
        return "exposure " + num(exposureStops) + " stops is not usable";
    if (!s.srgb && !(std::isfinite(s.gamma) && s.gamma > 0.0f))
        return "gamma must be positive and finite (got " + num(s.gamma) + ")";
    if (s.op == TonemapSettings::Operator::Photographic) {
        if (!(std::isfinite(s.key) && s.key > 0.0f))
            return "key value must be positive and finite (got " + num(s.key) + ")";
        if (!(s.burnPercent >= 0.0f && s.burnPercent <= 100.0f)) // also rejects NaN
            return "burn percentage must be in [0, 100] (got " + num(s.burnPercent) + ")";
        // A negative exponent would turn a zero channel of a coloured pixel into infinity.
        if (!(std::isfinite(s.saturation) && s.saturation >= 0.0f))
            return "saturation must be non-negative and finite (got " + num(s.saturation) + ")";
    }
    return "";
}

bool finiteRgb(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// The exact piecewise sRGB transfer function (IEC 61966-2-1), written in float exactly as
// image_io.cpp's writePng does, so that Clamp + sRGB reproduces its bytes.
float srgbOetf(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f; }

// Display encoding of one channel: clamp, transfer curve, 8-bit rounding.
class Encoder {
public:
    explicit Encoder(const TonemapSettings& s) : srgb_(s.srgb), invGamma_(1.0f / s.gamma) {}
    uint8_t operator()(float v) const {
        v = std::clamp(v, 0.0f, 1.0f);
        if (srgb_)
            v = srgbOetf(v);
        else if (invGamma_ != 1.0f) // gamma 1 (the course's "no tonemap") stays exact
            v = std::pow(v, invGamma_);
        return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    }

private:
    bool srgb_;
    float invGamma_;
};

void putMagenta(uint8_t* q) { q[0] = 255, q[1] = 0, q[2] = 255; }

// Maps every pixel p (RGBA floats) to its 3 bytes q with map(p, q); pixels with a non-finite R,
// G or B become magenta instead.
template <class Map>
void mapPixels(const Image& image, std::vector<uint8_t>& out, Map map) {
    const std::size_t n = out.size() / 3;
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = image.rgba.data() + 4 * i;
        uint8_t* q = out.data() + 3 * i;
        if (finiteRgb(p))
            map(p, q);
        else
            putMagenta(q);
    }
}

void clampOperator(const Image& image, const TonemapSettings& s, float exposureStops, std::vector<uint8_t>& out) {
    const Encoder encode(s);
    // float, like writePng; a product that overflows to +inf still clamps to 1.
    const float scale = s.scale * std::exp2(exposureStops);
    mapPixels(image, out, [&](const float* p, uint8_t* q) {
        for (int c = 0; c < 3; ++c) q[c] = encode(p[c] * scale);
    });
}

// Luminance of the pixel with negative channels treated as 0, before exposure. Done in
// double so that scaling and the log-average cannot overflow or lose the small pixels.
double luminance(const float* p) {
    return kTonemapLumR * std::max(0.0, double(p[0])) + kTonemapLumG * std::max(0.0, double(p[1])) +
           kTonemapLumB * std::max(0.0, double(p[2]));
}

void photographicOperator(
    const Image& image, const TonemapSettings& s, float exposureStops, std::vector<uint8_t>& out) {
    const Encoder encode(s);
    const double scale = std::exp2(double(exposureStops));
    const std::size_t n = out.size() / 3;
    const bool useWhite = s.burnPercent > 0.0f;

    // Pass 1: log-average over the finite pixels only; their luminances are also kept for
    // the percentile (the one O(n) buffer), since nth_element needs a copy it may reorder.
    double logSum = 0.0;
    std::size_t count = 0;
    std::vector<double> lums;
    if (useWhite) lums.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = image.rgba.data() + 4 * i;
        if (!finiteRgb(p)) continue;
        const double y = scale * luminance(p);
        logSum += std::log(kTonemapLogDelta + y);
        ++count;
        if (useWhite) lums.push_back(y);
    }

    double toL = 0.0;       // L = toL * Y (scaled Y), i.e. key / L_avg
    double invWhite2 = 0.0; // 1 / L_white^2; 0 means no white point (burn 0)
    if (count > 0) {
        // L_avg >= delta because every Y >= 0, so this division is safe.
        const double lAvg = std::exp(logSum / double(count));
        toL = double(s.key) / lAvg;
        if (useWhite) {
            // The brightest ceil(count*burn/100) pixels burn out (at least one: burn > 0).
            // burnPercent is a float, so e.g. 0.1 is 0.100000001; the relative slack (larger
            // than float rounding, 6e-8) keeps 1000 pixels at 0.1% from burning 2, not 1.
            const double exact = double(count) * double(s.burnPercent) / 100.0;
            const double burned = std::clamp(std::ceil(exact * (1.0 - 1e-7)), 1.0, double(count));
            const std::size_t idx = count - static_cast<std::size_t>(burned);
            std::nth_element(lums.begin(), lums.begin() + std::ptrdiff_t(idx), lums.end());
            const double white = toL * lums[idx];
            // white = 0 (burning everything on a mostly black image) or white^2 underflowing
            // gives +inf: every non-black pixel then saturates, the limit of the formula.
            invWhite2 = 1.0 / (white * white);
        }
        std::vector<double>().swap(lums); // release before the output pass
    }

    // Pass 2: map each pixel. Colour ratios use the unscaled channels (scale cancels).
    const double sat = s.saturation;
    mapPixels(image, out, [&](const float* p, uint8_t* q) {
        const double y0 = luminance(p);
        if (y0 <= 0.0) { // all channels <= 0: black, and no 0/0 in the colour ratio
            q[0] = q[1] = q[2] = 0;
            return;
        }
        const double l = toL * (scale * y0); // same rounding as the white point's L
        double ld = useWhite ? l * (1.0 + l * invWhite2) / (1.0 + l) : l / (1.0 + l);
        // With an infinite white term ld is +inf; cap it so that a zero channel ratio below
        // gives 0 rather than inf * 0 = NaN (finite ratios still clamp to 1).
        ld = std::min(ld, DBL_MAX);
        for (int c = 0; c < 3; ++c) {
            const double ratio = std::max(0.0, double(p[c])) / y0;
            // saturation 1 is the common case: skip pow so hue ratios stay exact.
            const double co = ld * (sat == 1.0 ? ratio : std::pow(ratio, sat));
            q[c] = encode(static_cast<float>(std::min(co, 1.0)));
        }
    });
}

// Error type of the PNG writer: its messages already carry the "<path>: " prefix.
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
    throw std::runtime_error(path.string() + ": " + problem);
}

} // namespace

std::vector<uint8_t> tonemapToRgb8(const Image& image, const TonemapSettings& settings, float exposureStops) {
    if (const std::string problem = argumentProblem(image, settings, exposureStops); !problem.empty())
        throw std::invalid_argument("tonemap: " + problem);
    std::vector<uint8_t> out(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
    if (settings.op == TonemapSettings::Operator::Photographic)
        photographicOperator(image, settings, exposureStops, out);
    else
        clampOperator(image, settings, exposureStops, out);
    return out;
}

void writeTonemappedPng(
    const std::filesystem::path& path, const Image& image, const TonemapSettings& settings, float exposureStops) {
    // Checked here rather than by catching invalid_argument, so the message is the plain
    // problem after the path, like every other error of this function.
    if (const std::string problem = argumentProblem(image, settings, exposureStops); !problem.empty())
        fail(path, problem);
    if (image.width == 0 || image.height == 0)
        fail(path,
            "cannot write an empty image (" + std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
    writePngRgb8(path, image.width, image.height, tonemapToRgb8(image, settings, exposureStops));
}

void writePng(const std::filesystem::path& path, const Image& image, float exposureStops) {
    writeTonemappedPng(path, image, TonemapSettings{}, exposureStops); // clamp + sRGB curve
}

} // namespace pt
