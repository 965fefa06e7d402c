// Owen-scrambled Sobol' points with per-pixel shuffling (Burley, "Practical Hash-based Owen
// Scrambling", JCGT 2020), padded in 2D: every 2D sample a path asks for (pixel jitter, lens,
// each vertex's light point and BSDF direction) is the first two Sobol' dimensions, a
// (0,2)-sequence, with its own index shuffle and scramble seeded by (pixel, dimension, seed).
// Each 2D projection is then stratified for any power-of-two prefix of samples while
// pixels and dimensions stay uncorrelated.
#ifndef PT_COMMON_SOBOL_GLSL
#define PT_COMMON_SOBOL_GLSL

// First Sobol' dimension: the van der Corput radical inverse in base 2.
uint sobolDimension0(uint index) { return bitfieldReverse(index); }

// Second Sobol' dimension: direction numbers v_0 = 2^31, v_k = v_(k-1) ^ (v_(k-1) >> 1), the
// Pascal matrix mod 2. By Lucas' theorem C(k, j) is odd exactly when the bits of j are a subset
// of those of k, so bit j of the result (counted from the top) is the parity of the index bits
// k that are supersets of j: a superset-parity transform, five masked shifts, then the reversal.
// Branch-free, unlike the loop over set bits (the same value for all 2^32 indices, checked on
// the CPU), so the lanes of a SIMD group no longer wait for the one with the longest index.
uint sobolDimension1Reversed(uint index) {
    uint x = index;
    x ^= (x >> 1u) & 0x55555555u;
    x ^= (x >> 2u) & 0x33333333u;
    x ^= (x >> 4u) & 0x0f0f0f0fu;
    x ^= (x >> 8u) & 0x00ff00ffu;
    x ^= (x >> 16u) & 0x0000ffffu;
    return x;
}
uint sobolDimension1(uint index) { return bitfieldReverse(sobolDimension1Reversed(index)); }

// Nested uniform (Owen) scrambling of a word held bit-reversed (its lowest bit is the binary
// fraction's first digit): each bit is flipped by a function of the bits below it, which is
// where multiplication carries run. Constants after Vegdahl, "Building a Better LK Hash" (2021).
uint owenScrambleReversed(uint x, uint seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

// A random permutation of 32-bit words in which each bit is flipped by a function of the bits
// above it: Owen scrambling of x as a binary fraction.
uint owenScramble(uint x, uint seed) { return bitfieldReverse(owenScrambleReversed(bitfieldReverse(x), seed)); }

// The 2D point of sample `index` for one (pixel, dimension) stream, as two 32-bit fractions.
// Owen-scrambling the index keeps every aligned block of 2^k indices an aligned block, so
// the first 2^k samples of a pixel are a scrambled (0,k,2)-net. Written without the reversal
// pairs that cancel: owenScramble(sobolDimension0(s)) = reverse(scrambleReversed(s)), and
// owenScramble(sobolDimension1(s)) = reverse(scrambleReversed(sobolDimension1Reversed(s))).
uvec2 sobolOwen2(uint index, uvec3 seeds) {
    uint shuffled = owenScramble(index, seeds.x);
    return uvec2(bitfieldReverse(owenScrambleReversed(shuffled, seeds.y)),
        bitfieldReverse(owenScrambleReversed(sobolDimension1Reversed(shuffled), seeds.z)));
}

#endif
