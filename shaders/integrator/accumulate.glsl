// Per-pixel running sums as double-floats (hi + lo): a float32 running sum of 1e5 samples
// drifts by ~1e-3 relative (each add rounds to ulp(sum) / 2, ~2e-3 at 3e4), which would make a
// constant-radiance pixel visibly wrong and checkpoints/merges inexact. Each add is an
// error-free transformation: the rounding error of hi + x is computed exactly and kept in lo.
// The state (hi, lo) is what is stored, so splitting the samples over dispatches, tiles or
// resumed runs gives bit-identical sums.
#ifndef PT_INTEGRATOR_ACCUMULATE_GLSL
#define PT_INTEGRATOR_ACCUMULATE_GLSL
#include "shared/layout.h"
#include "common/buffers.glsl"
#include "common/math.glsl"

// Knuth's TwoSum (TAOCP vol. 2, 4.2.2): s = fl(a + b) and err with a + b = s + err exactly,
// for any magnitudes. `precise` (SPIR-V NoContraction) stops the compiler from fusing or
// simplifying (s - a) - b to zero, which would silently turn this back into a plain sum.
void twoSum(vec3 a, vec3 b, out vec3 s, out vec3 err) {
    precise vec3 sum = a + b;
    precise vec3 bVirtual = sum - a;
    precise vec3 aVirtual = sum - bVirtual;
    precise vec3 e = (a - aVirtual) + (b - bVirtual);
    s = sum;
    err = e;
}

// (hi, lo) += x: TwoSum of hi and x, the error folded into lo, then renormalised by a second
// TwoSum so |lo| <= ulp(hi) / 2 (a double-float, ~48 significant bits; Dekker 1971).
void accumulate(inout vec3 hi, inout vec3 lo, vec3 x) {
    vec3 s, err;
    twoSum(hi, x, s, err);
    precise vec3 e = err + lo;
    twoSum(s, e, hi, lo);
}

// A pixel's running sums while an invocation adds samples to them, and their place in the
// accumulation buffer (ACCUM_* in shared/layout.h).
struct PixelSums {
    vec4 sum; // rgb: radiance sum (hi); w: samples dropped as not finite
    vec3 sumLo;
    vec3 sumSquares;
    vec3 sumSquaresLo;
};

PixelSums loadPixelSums(Vec4Ref accumulation, uint base) {
    PixelSums sums;
    sums.sum = accumulation.v[base + ACCUM_SUM];
    sums.sumLo = accumulation.v[base + ACCUM_SUM_LO].rgb;
    sums.sumSquares = accumulation.v[base + ACCUM_SUM_SQUARES].rgb;
    sums.sumSquaresLo = accumulation.v[base + ACCUM_SUM_SQUARES_LO].rgb;
    return sums;
}

void storePixelSums(Vec4Ref accumulation, uint base, PixelSums sums) {
    accumulation.v[base + ACCUM_SUM] = sums.sum;
    accumulation.v[base + ACCUM_SUM_LO] = vec4(sums.sumLo, 0.0);
    accumulation.v[base + ACCUM_SUM_SQUARES] = vec4(sums.sumSquares, 0.0);
    accumulation.v[base + ACCUM_SUM_SQUARES_LO] = vec4(sums.sumSquaresLo, 0.0);
}

// Adds one sample; a sample that is not finite is counted as dropped and contributes zero.
void addToPixelSums(inout PixelSums sums, vec3 L) {
    if (allFinite(L)) {
        vec3 sumHi = sums.sum.rgb;
        accumulate(sumHi, sums.sumLo, L);
        sums.sum.rgb = sumHi;
        accumulate(sums.sumSquares, sums.sumSquaresLo, L * L);
    } else {
        sums.sum.w += 1.0;
    }
}

#endif
