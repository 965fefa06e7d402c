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

float scaleOf(uint32_t biased) {
    const uint32_t bits = biased << 23;
    float s;
    std::memcpy(&s, &bits, sizeof s);
    return s;
}

// The decoded plane, as the kernel computes it: q * scale is exact (q < 2^8 times a power of
// two), so this is one rounded addition wherever it runs, fused into an fma or not.
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
        // The smallest scale whose top step reaches the far side (inf past 2^127 reaches anything),
        // searched up from just below the exponent of (hi - lo) / 255.
        uint32_t biased = kMinBiased;
        if (const double extent = double(hi) - double(lo); extent > 0.0) {
            int e = 0;
            std::frexp(extent / double(kMaxQ), &e); // extent / 255 <= 2^e
            biased = uint32_t(std::clamp(e - 1 + 127, int(kMinBiased), int(kMaxBiased)));
        }
        while (biased < kMaxBiased && !(decodePlane(lo, kMaxQ, scaleOf(biased)) >= hi)) ++biased;
        const float scale = scaleOf(biased);
        uint32_t loBytes = 0, hiBytes = 0;
        for (int i = 0; i < kWidth; ++i) {
            if (node.child[i] == BVH4_EMPTY) continue;
            const float childLo = slot(axes[a].lo, i), childHi = slot(axes[a].hi, i);
            // Outwards: the largest step at or below the low plane, the smallest at or above the
            // high one, starting from the rounded quotient and corrected in the decoder's arithmetic.
            double guess = std::floor((double(childLo) - double(lo)) / double(scale));
            uint32_t qlo = uint32_t(std::clamp(guess, 0.0, double(kMaxQ)));
            while (qlo > 0 && decodePlane(lo, qlo, scale) > childLo) --qlo;
            guess = std::ceil((double(childHi) - double(lo)) / double(scale));
            uint32_t qhi = uint32_t(std::clamp(guess, 0.0, double(kMaxQ)));
            while (qhi < kMaxQ && decodePlane(lo, qhi, scale) < childHi) ++qhi;
            loBytes |= qlo << (8 * i);
            hiBytes |= qhi << (8 * i);
        }
        q.origin[a] = lo;
        q.exponents |= biased << (8 * a);
        q.lo[a] = loBytes;
        q.hi[a] = hiBytes;
    }
    return q;
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
