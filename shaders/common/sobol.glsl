// Owen-scrambled Sobol' points with per-pixel shuffling (Burley, "Practical Hash-based Owen
// Scrambling", JCGT 2020), padded in 2D: every 2D sample a path asks for (pixel jitter, lens,
// each vertex's light point and BSDF direction) is the first two Sobol' dimensions, a
// (0,2)-sequence, with its own index shuffle and scramble seeded by (pixel, dimension, seed).
// Each 2D projection is then stratified for any power-of-two prefix of samples while
// pixels and dimensions stay uncorrelated. Consecutive bounces' directions are paired into 4D
// points (sobolOwenUpper2, common/rng.glsl).
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

// Sobol' dimensions 2 and 3 (counted from 0), the upper half of a 4D point whose lower half is
// sobolOwen2's pair: generator matrix columns (column k is the value of index 2^k) from Joe and
// Kuo's direction numbers (primitive polynomials x^2 + x + 1 and x^3 + x + 1, initial m = 1, 3 and
// 1, 3, 1; "Constructing Sobol sequences with better two-dimensional projections", 2008). Of the
// pairs among dimensions 2-7 this one keeps the best nets: the first 2^m points (m <= 10) are a
// (t, m, 2)-net with t <= 2 in dimensions 2-3 and a (t, m, 4)-net with t <= 3 in all four.
const uint SOBOL_DIMENSION2[32] = uint[32](0x80000000u, 0xc0000000u, 0x60000000u, 0x90000000u, 0xe8000000u, 0x5c000000u,
    0x8e000000u, 0xc5000000u, 0x68800000u, 0x9cc00000u, 0xee600000u, 0x55900000u, 0x80680000u, 0xc09c0000u, 0x60ee0000u,
    0x90550000u, 0xe8808000u, 0x5cc0c000u, 0x8e606000u, 0xc5909000u, 0x6868e800u, 0x9c9c5c00u, 0xeeee8e00u, 0x5555c500u,
    0x8000e880u, 0xc0005cc0u, 0x60008e60u, 0x9000c590u, 0xe8006868u, 0x5c009c9cu, 0x8e00eeeeu, 0xc5005555u);
const uint SOBOL_DIMENSION3[32] = uint[32](0x80000000u, 0xc0000000u, 0x20000000u, 0x50000000u, 0xf8000000u, 0x74000000u,
    0xa2000000u, 0x93000000u, 0xd8800000u, 0x25400000u, 0x59e00000u, 0xe6d00000u, 0x78080000u, 0xb40c0000u, 0x82020000u,
    0xc3050000u, 0x208f8000u, 0x51474000u, 0xfbea2000u, 0x75d93000u, 0xa0858800u, 0x914e5400u, 0xdbe79e00u, 0x25db6d00u,
    0x58800080u, 0xe54000c0u, 0x79e00020u, 0xb6d00050u, 0x800800f8u, 0xc00c0074u, 0x200200a2u, 0x50050093u);

// Dimensions 2 and 3 of point `index`: the XOR of the columns of its set bits, 32 masked XORs
// (branch-free, as sobolDimension1Reversed).
uvec2 sobolDimensions23(uint index) {
    uvec2 x = uvec2(0u);
    for (int k = 0; k < 32; ++k)
        x ^= uvec2(SOBOL_DIMENSION2[k], SOBOL_DIMENSION3[k]) & uvec2(0u - ((index >> uint(k)) & 1u));
    return x;
}

// Dimensions 2 and 3 of the point whose dimensions 0 and 1 are sobolOwen2(index, seeds) of the
// stream with seeds.x == shuffleSeed: the same index shuffle, so the four values are one point of
// a scrambled 4D Sobol' sequence; each value Owen-scrambled with its own seed.
uvec2 sobolOwenUpper2(uint index, uint shuffleSeed, uvec2 scrambleSeeds) {
    uvec2 x = sobolDimensions23(owenScramble(index, shuffleSeed));
    return uvec2(owenScramble(x.x, scrambleSeeds.x), owenScramble(x.y, scrambleSeeds.y));
}

#endif
