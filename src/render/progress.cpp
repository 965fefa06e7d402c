#include "render/progress.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unistd.h>

namespace pt {

Progress::Progress(uint32_t targetSpp, double targetSeconds, bool enabled)
    : targetSpp_(targetSpp), targetSeconds_(targetSeconds), enabled_(enabled), terminal_(isatty(fileno(stderr)) != 0) {}

void Progress::update(uint32_t spp, double seconds, double mpathsPerSecond, double relMse) {
    if (!enabled_) return;
    double fraction = targetSpp_ > 0 ? double(spp) / targetSpp_ : seconds / std::max(1e-9, targetSeconds_);
    fraction = std::clamp(fraction, 0.0, 1.0);
    const double eta = fraction > 0 ? seconds * (1.0 - fraction) / fraction : 0.0;
    if (terminal_) {
        const int width = 30;
        const int filled = static_cast<int>(fraction * width + 0.5);
        std::string bar(filled, '#');
        bar.resize(width, ' ');
        std::fprintf(stderr, "\r[%s] %u spp  %.1f s  ETA %.1f s  %.2f M paths/s", bar.c_str(), spp, seconds, eta,
            mpathsPerSecond);
        if (!std::isnan(relMse)) std::fprintf(stderr, "  relMSE %.3g", relMse);
        std::fprintf(stderr, "   ");
        std::fflush(stderr);
        drewBar_ = true;
    } else if (seconds - lastPrint_ >= 5.0) {
        std::fprintf(stderr, "pt: %u spp, %.1f s, ETA %.1f s, %.2f M paths/s", spp, seconds, eta, mpathsPerSecond);
        if (!std::isnan(relMse)) std::fprintf(stderr, ", relMSE %.4g", relMse);
        std::fprintf(stderr, "\n");
        lastPrint_ = seconds;
    }
}

void Progress::finish() {
    if (drewBar_) std::fprintf(stderr, "\n");
    drewBar_ = false;
}

} // namespace pt
