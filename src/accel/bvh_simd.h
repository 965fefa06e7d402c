// SIMD building blocks of the BVH builder (src/accel/bvh.cpp): a 4-lane float vector (SSE2, or a
// scalar twin with the same results), the builder's primitive record and its box type.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <limits>

// PT_BVH_SSE=0 forces the portable scalar path (it gives bit-identical trees).
#ifndef PT_BVH_SSE
#if defined(__SSE2__) || defined(_M_X64)
#define PT_BVH_SSE 1
#else
#define PT_BVH_SSE 0
#endif
#endif
#if PT_BVH_SSE
#include <emmintrin.h>
#endif

namespace pt::bvh_detail {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Working copy of a primitive, permuted in place (contiguous memory is much faster to bin and
// partition than gathering through an index array). Laid out as two 16-byte rows so a box loads
// as two SIMD registers (lane 3, prim / binKeys, is zeroed on load). binKeys caches each axis' bin from the last binning pass, so the partition uses
// exactly the classification the SAH was evaluated on, with no recomputation that could round
// differently.
struct alignas(16) PrimRef {
    float lo[3];
    uint32_t prim;
    float hi[3];
    uint32_t binKeys;
};
static_assert(sizeof(PrimRef) == 32);

// Minimal 4-lane float vector: SSE2 where available, else a scalar twin with the same semantics
// (min/max return the second operand when unordered, like minps/maxps), so results match.
struct V4 {
#if PT_BVH_SSE
    __m128 v;
#else
    float v[4];
#endif
};

#if PT_BVH_SSE
inline V4 splat(float f) { return {_mm_set1_ps(f)}; }
inline V4 set3(float x, float y, float z) { return {_mm_set_ps(0.0f, z, y, x)}; }
inline V4 loadRow(const void* p) { return {_mm_load_ps(static_cast<const float*>(p))}; }
inline void store(float* p, V4 a) { _mm_storeu_ps(p, a.v); }
inline V4 vmin(V4 a, V4 b) { return {_mm_min_ps(a.v, b.v)}; }
inline V4 vmax(V4 a, V4 b) { return {_mm_max_ps(a.v, b.v)}; }
inline V4 vadd(V4 a, V4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline V4 vsub(V4 a, V4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline V4 vmul(V4 a, V4 b) { return {_mm_mul_ps(a.v, b.v)}; }
inline V4 xyz(V4 a) { return {_mm_and_ps(a.v, _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1)))}; } // lane 3 = 0
inline void truncToInt(V4 a, int32_t out[4]) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(a.v));
}
// Lanes of a where `take` is true, else of b (branch-free).
inline V4 select(bool take, V4 a, V4 b) {
    const __m128 m = _mm_castsi128_ps(_mm_set1_epi32(-int32_t(take)));
    return {_mm_or_ps(_mm_and_ps(m, a.v), _mm_andnot_ps(m, b.v))};
}
#else
template <class F>
inline V4 lanes(V4 a, V4 b, F f) {
    V4 r;
    for (int i = 0; i < 4; ++i) r.v[i] = f(a.v[i], b.v[i]);
    return r;
}
inline V4 splat(float f) { return {{f, f, f, f}}; }
inline V4 set3(float x, float y, float z) { return {{x, y, z, 0.0f}}; }
inline V4 loadRow(const void* p) {
    V4 r;
    std::memcpy(r.v, p, sizeof r.v);
    return r;
}
inline void store(float* p, V4 a) { std::memcpy(p, a.v, sizeof a.v); }
inline V4 vmin(V4 a, V4 b) {
    return lanes(a, b, [](float x, float y) { return x < y ? x : y; });
}
inline V4 vmax(V4 a, V4 b) {
    return lanes(a, b, [](float x, float y) { return x > y ? x : y; });
}
inline V4 vadd(V4 a, V4 b) {
    return lanes(a, b, [](float x, float y) { return x + y; });
}
inline V4 vsub(V4 a, V4 b) {
    return lanes(a, b, [](float x, float y) { return x - y; });
}
inline V4 vmul(V4 a, V4 b) {
    return lanes(a, b, [](float x, float y) { return x * y; });
}
inline V4 xyz(V4 a) {
    a.v[3] = 0.0f;
    return a;
}
inline V4 select(bool take, V4 a, V4 b) { return take ? a : b; }
inline void truncToInt(V4 a, int32_t out[4]) {
    for (int i = 0; i < 4; ++i) out[i] = int32_t(a.v[i]);
}
#endif

// Position of keys[i] in the ascending order of keys[0, nPadded), ties broken by index. nPadded
// is a multiple of 4 and the padding keys are +inf (real keys are finite, so it never counts).
// Branch-free: used by the small-node sort, where comparison sorts mispredict a lot.
#if PT_BVH_SSE
inline int rankOf(const float* keys, int nPadded, int i) {
    const __m128 ki = _mm_set1_ps(keys[i]);
    const __m128i ii = _mm_set1_epi32(i);
    __m128i idx = _mm_set_epi32(3, 2, 1, 0);
    __m128i count = _mm_setzero_si128();
    for (int b = 0; b < nPadded; b += 4) {
        const __m128 kj = _mm_loadu_ps(keys + b);
        const __m128 tieBefore = _mm_and_ps(_mm_cmpeq_ps(kj, ki), _mm_castsi128_ps(_mm_cmplt_epi32(idx, ii)));
        const __m128 before = _mm_or_ps(_mm_cmplt_ps(kj, ki), tieBefore);
        count = _mm_sub_epi32(count, _mm_castps_si128(before)); // true lanes are -1
        idx = _mm_add_epi32(idx, _mm_set1_epi32(4));
    }
    count = _mm_add_epi32(count, _mm_shuffle_epi32(count, _MM_SHUFFLE(1, 0, 3, 2)));
    count = _mm_add_epi32(count, _mm_shuffle_epi32(count, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtsi128_si32(count);
}
#else
inline int rankOf(const float* keys, int nPadded, int i) {
    int rank = 0;
    for (int j = 0; j < nPadded; ++j) rank += int(keys[j] < keys[i]) | (int(keys[j] == keys[i]) & int(j < i));
    return rank;
}
#endif

// Lane 3 (integer payload) is zeroed so that it never feeds arithmetic as a denormal or NaN.
inline V4 loadLo(const PrimRef& r) { return xyz(loadRow(&r.lo[0])); }
inline V4 loadHi(const PrimRef& r) { return xyz(loadRow(&r.hi[0])); }
// (lo + hi) * 0.5 rather than lo * 0.5 + hi * 0.5: no FMA contraction can make two call sites
// round differently. Overflows only beyond 1.7e38.
inline V4 centroidOf(V4 lo, V4 hi) { return vmul(vadd(lo, hi), splat(0.5f)); }

struct Box4 {
    V4 lo = splat(kInf);
    V4 hi = splat(-kInf);

    void grow(V4 plo, V4 phi) {
        lo = vmin(lo, plo);
        hi = vmax(hi, phi);
    }
    void grow(V4 p) { grow(p, p); }
    void grow(const Box4& b) { grow(b.lo, b.hi); }
    void grow(const PrimRef& r) { grow(loadLo(r), loadHi(r)); }
    // Only meaningful for non-empty boxes. 2 ((dx dy + dy dz) + dz dx) on both paths, the same
    // products summed in the same order, so SSE and scalar builds agree bit for bit.
    float area() const {
#if PT_BVH_SSE
        const __m128 d = _mm_sub_ps(hi.v, lo.v);
        const __m128 p = _mm_mul_ps(d, _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1))); // dx dy, dy dz, dz dx
        const __m128 s = _mm_add_ss(p, _mm_shuffle_ps(p, p, _MM_SHUFFLE(1, 1, 1, 1)));
        return 2.0f * _mm_cvtss_f32(_mm_add_ss(s, _mm_movehl_ps(p, p)));
#else
        float d[4];
        store(d, vsub(hi, lo));
        return 2.0f * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
#endif
    }
    glm::vec3 lo3() const {
        float f[4];
        store(f, lo);
        return {f[0], f[1], f[2]};
    }
    glm::vec3 hi3() const {
        float f[4];
        store(f, hi);
        return {f[0], f[1], f[2]};
    }
};

// Grows `left` or `right` by the centroid c, branch-free (during a partition the side is
// unpredictable): the other box is grown by an empty point (+inf low, -inf high).
inline void addCentroidToSide(V4 c, bool isLeft, Box4& left, Box4& right) {
    const V4 inf = splat(kInf), negInf = splat(-kInf);
    left.lo = vmin(left.lo, select(isLeft, c, inf));
    left.hi = vmax(left.hi, select(isLeft, c, negInf));
    right.lo = vmin(right.lo, select(isLeft, inf, c));
    right.hi = vmax(right.hi, select(isLeft, negInf, c));
}

} // namespace pt::bvh_detail
