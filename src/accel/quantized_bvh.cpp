#include "accel/quantized_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace pt {
namespace {

constexpr int kWidth = 4;
constexpr uint32_t kMaxQ = 255;
// Biased exponents of normal float scales: 2^-126 .. 2^127.
constexpr uint32_t kMinBiased = 1, kMaxBiased = 254;
// Scales of axes with an extent stay at or above 2^-80, so that the kernel's scale / direction
// (shaders/geometry/traverse.glsl, quantizedChildEntries) never flushes to zero for directions
// up to 2^40 long. Finer steps are only lost on boxes below 1e-22 across.
constexpr uint32_t kMinExtentBiased = 127 - 80;
// Every decoded plane origin + q * scale is exact when the origin is an integer multiple k of the
// scale with |k| + 255 below 2^24 (a float's significand): (k + q) * scale is a float.
constexpr double kExactSteps = double(1 << 24) - double(kMaxQ) - 1.0;

float scaleOf(uint32_t biased) {
    const uint32_t bits = biased << 23;
    float s;
    std::memcpy(&s, &bits, sizeof s);
    return s;
}

// The decoded plane, as the kernel computes it: q * scale is exact (q < 2^8 times a power of
// two), and so is the addition, the origin being a multiple of the scale (but near the float
// range's end): the same value wherever it runs, fused into an fma or not.
float decodePlane(float origin, uint32_t q, float scale) { return origin + float(q) * scale; }

float slot(const glm::vec4& v, int i) { return v[i]; }

struct Axis {
    const glm::vec4& lo;
    const glm::vec4& hi;
};

} // namespace

gpu::GpuBvh4QNode quantizeWideNode(const gpu::GpuBvh4Node& node) {
    gpu::GpuBvh4QNode q{};
    q.child = node.child;
    const Axis axes[3] = {{node.loX, node.hiX}, {node.loY, node.hiY}, {node.loZ, node.hiZ}};
    for (int a = 0; a < 3; ++a) {
        float lo = std::numeric_limits<float>::max(), hi = -std::numeric_limits<float>::max();
        for (int i = 0; i < kWidth; ++i) {
            if (node.child[i] == BVH4_EMPTY) continue;
            lo = std::min(lo, slot(axes[a].lo, i));
            hi = std::max(hi, slot(axes[a].hi, i));
        }
        if (lo > hi) lo = hi = 0.0f; // no child at all
        // The smallest scale whose top step reaches the far side from the origin (`lo` rounded
        // down to a multiple of the scale, so that every decoded plane is exact), searched up from
        // just below the exponent of (hi - lo) / 255. A flat axis keeps origin lo and q = 0.
        uint32_t biased = kMinBiased;
        float origin = lo;
        if (const double extent = double(hi) - double(lo); extent > 0.0) {
            int e = 0;
            std::frexp(extent / double(kMaxQ), &e); // extent / 255 <= 2^e
            biased = uint32_t(std::clamp(e - 1 + 127, int(kMinExtentBiased), int(kMaxBiased)));
            for (;; ++biased) {
                const double s = double(scaleOf(biased));
                const double k = std::floor(double(lo) / s);
                origin = float(k * s);
                const bool exact = std::abs(k) <= kExactSteps && std::isfinite(origin);
                if (biased == kMaxBiased || (exact && double(origin) + double(kMaxQ) * s >= double(hi))) break;
            }
            // Only near the float range's end (never in a tree quantizable() admits): the old origin,
            // decoded with rounding and kept conservative by the corrections below.
            if (!std::isfinite(origin) || double(origin) + double(kMaxQ) * double(scaleOf(biased)) < double(hi))
                origin = lo;
        }
        const float scale = scaleOf(biased);
        uint32_t loBytes = 0, hiBytes = 0;
        for (int i = 0; i < kWidth; ++i) {
            if (node.child[i] == BVH4_EMPTY) continue;
            const float childLo = slot(axes[a].lo, i), childHi = slot(axes[a].hi, i);
            // Outwards: the largest step at or below the low plane, the smallest at or above the
            // high one, starting from the rounded quotient and corrected in the decoder's arithmetic.
            double guess = std::floor((double(childLo) - double(origin)) / double(scale));
            uint32_t qlo = uint32_t(std::clamp(guess, 0.0, double(kMaxQ)));
            while (qlo > 0 && decodePlane(origin, qlo, scale) > childLo) --qlo;
            guess = std::ceil((double(childHi) - double(origin)) / double(scale));
            uint32_t qhi = uint32_t(std::clamp(guess, 0.0, double(kMaxQ)));
            while (qhi < kMaxQ && decodePlane(origin, qhi, scale) < childHi) ++qhi;
            loBytes |= qlo << (8 * i);
            hiBytes |= qhi << (8 * i);
        }
        q.origin[a] = origin;
        q.exponents |= biased << (8 * a);
        q.lo[a] = loBytes;
        q.hi[a] = hiBytes;
    }
    return q;
}

bool quantizable(const std::vector<gpu::GpuBvh4Node>& nodes) {
    constexpr float kLimit = 1152921504606846976.0f; // 2^60
    for (const gpu::GpuBvh4Node& n : nodes)
        for (int i = 0; i < kWidth; ++i) {
            if (n.child[i] == BVH4_EMPTY) continue;
            const float extremes[6] = {n.loX[i], n.loY[i], n.loZ[i], n.hiX[i], n.hiY[i], n.hiZ[i]};
            for (float v : extremes)
                if (!(std::abs(v) <= kLimit)) return false;
        }
    return true;
}

std::vector<gpu::GpuBvh4QNode> quantizeWideNodes(const std::vector<gpu::GpuBvh4Node>& nodes) {
    std::vector<gpu::GpuBvh4QNode> out;
    out.reserve(nodes.size());
    for (const gpu::GpuBvh4Node& n : nodes) out.push_back(quantizeWideNode(n));
    return out;
}

gpu::GpuBvh4Node decodeWideNode(const gpu::GpuBvh4QNode& q) {
    gpu::GpuBvh4Node n{};
    n.child = q.child;
    glm::vec4* lo[3] = {&n.loX, &n.loY, &n.loZ};
    glm::vec4* hi[3] = {&n.hiX, &n.hiY, &n.hiZ};
    constexpr float kMax = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a) {
        const float scale = scaleOf((q.exponents >> (8 * a)) & 0xffu);
        for (int i = 0; i < kWidth; ++i) {
            const bool used = q.child[i] != BVH4_EMPTY;
            (*lo[a])[i] = used ? decodePlane(q.origin[a], (q.lo[a] >> (8 * i)) & 0xffu, scale) : kMax;
            (*hi[a])[i] = used ? decodePlane(q.origin[a], (q.hi[a] >> (8 * i)) & 0xffu, scale) : -kMax;
        }
    }
    return n;
}

} // namespace pt
