#pragma once
// Rays for the traversal tests (shaders/tests/test_kernels.comp's trace modes): a test ray, and
// random origins and directions.
#include "shared/layout.h"

#include <glm/glm.hpp>

#include <limits>
#include <random>

namespace pt::test {

inline gpu::GpuTestRay makeRay(glm::vec3 origin, glm::vec3 direction, float tMax = std::numeric_limits<float>::max()) {
    gpu::GpuTestRay r{};
    r.origin = origin;
    r.direction = direction;
    r.tMax = tMax;
    return r;
}

// A uniformly random unit vector.
inline glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> n;
    for (;;) {
        const glm::vec3 v(n(rng), n(rng), n(rng));
        const float len = glm::length(v);
        if (len > 1e-3f) return v / len;
    }
}

// A uniformly random point of the box [lo, hi].
inline glm::vec3 randomIn(std::mt19937& rng, glm::vec3 lo, glm::vec3 hi) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    return lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
}

} // namespace pt::test
