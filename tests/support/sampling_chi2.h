#pragma once
// Chi-square tests of the production samplers on the device, through
// shaders/tests/test_kernels.comp: each sampler's directions are histogrammed over
// (cos theta, phi) bins, which have equal solid angle for equal extents, and compared by a
// chi-square test against the counts its own pdf predicts. A sampler whose pdf does not describe
// its samples biases every estimator that divides by that pdf. The hemisphere samplers' tests are
// tests/shaders/common/sampling_chi2_test.cpp, the light samplers' are
// tests/shaders/lights/light_sampling_chi2_test.cpp.
#include "support/gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace pt::test {

inline constexpr double kPi = std::numbers::pi;
inline constexpr uint32_t kSamples = 200000;
inline constexpr double kMinPValue = 1e-3;

// Bins over cos theta in [zLo, zHi] by phi in [0, 2 pi): solid angle dz dphi, so every bin of
// a grid covers the same solid angle.
struct DirectionGrid {
    int zBins, phiBins;
    double zLo, zHi;

    int count() const { return zBins * phiBins; }
    double dz() const { return (zHi - zLo) / zBins; }
    double dphi() const { return 2.0 * kPi / phiBins; }
    int index(int zi, int pi) const { return zi * phiBins + pi; }

    int binOf(glm::vec3 w) const {
        const double z = std::clamp(double(w.z), zLo, zHi);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0.0) phi += 2.0 * kPi;
        const int zi = std::min(int((z - zLo) / dz()), zBins - 1);
        const int pi = std::min(int(phi / dphi()), phiBins - 1);
        return index(zi, pi);
    }
};

inline const DirectionGrid kHemisphere{16, 32, 0.0, 1.0};
inline const DirectionGrid kSphere{32, 64, -1.0, 1.0};

inline glm::vec3 directionAt(double z, double phi) {
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

inline std::vector<double> histogram(const DirectionGrid& grid, const std::vector<glm::vec4>& samples) {
    std::vector<double> counts(grid.count(), 0.0);
    for (const glm::vec4& s : samples) counts[grid.binOf(glm::vec3(s))] += 1.0;
    return counts;
}

inline double pValue(const std::vector<double>& observed, const std::vector<double>& expected, const char* what) {
    int dof = 0;
    const double p = pt::test::chiSquarePValue(observed, expected, &dof);
    std::printf("[          ] %s: chi-square p-value %.4g (%d degrees of freedom)\n", what, p, dof);
    return p;
}

// The fixture of every sampler test.
class SamplingTest : public GpuTest {};

} // namespace pt::test
