// Per-pixel running sums as double-floats (hi + lo): a float32 running sum of 1e5 samples
// drifts by ~1e-3 relative (each add rounds to ulp(sum) / 2, ~2e-3 at 3e4), which would make a
// constant-radiance pixel visibly wrong and checkpoints/merges inexact. Each add is an
// error-free transformation: the rounding error of hi + x is computed exactly and kept in lo.
// The state (hi, lo) is what is stored, so splitting the samples over dispatches, tiles or
// resumed runs gives bit-identical sums.
#ifndef PT_INTEGRATOR_ACCUMULATE_GLSL
#define PT_INTEGRATOR_ACCUMULATE_GLSL

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

#endif
