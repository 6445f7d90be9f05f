// Random numbers. Every value is a pure function of (seed, pixel, sample index,
// slot), so any split of the sample range over runs or machines draws exactly the
// same numbers (docs/architecture.md, principle 4), and both backends agree bit for
// bit: everything here is integer arithmetic.
//
// A sample's numbers come in slots, each one number (rng_1d) or a pair (rng_2d),
// taken in order or at a fixed place (rng_seek; the layout is in constants.glsl).
// render.sampler picks where they come from:
//   hash   every slot of every sample hashed independently (pcg4d below);
//   sobol  per pixel and slot, the samples 0, 1, 2, ... of the pixel take the points
//          of the first two Sobol dimensions, Owen-scrambled and shuffled by hashing
//          (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020): each slot's
//          first 2^k samples form a (0, k, 2)-net, stratified in every elementary
//          interval, and slots and pixels are scrambled independently, so they do
//          not correlate. Pairing two dimensions per slot ("padding") keeps every
//          slot in the best-stratified dimensions, however many a path draws.

// pcg4d from Jarzynski & Olano, "Hash Functions for GPU Rendering" (JCGT 2020): an
// LCG step on each lane, then two rounds of cross-lane multiply-adds around an
// xorshift.
uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + uvec4(1013904223u);
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v = v ^ (v >> 16u);
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

// A hash's top 24 bits as a float in [0, 1), scaled by 2^-24: every one of them is
// exactly a float, so the conversion does not round, and 1.0 is never reached (the
// largest value is 1 - 2^-24). Converting all 32 bits would round the top 128 values
// of 2^32 up to exactly 1.0, and a sampler given u = 1 picks past its last bin.
float unit_float(uint bits) {
    return float(bits >> 8u) * (1.0f / 16777216.0f);
}

// The numbers of one sample of one pixel; `dim` is the next slot.
struct Rng {
    uvec4 key;  // pixel, sample index, seed, unused
    uint dim;
};

Rng rng_start(uint pixel_index, uint sample_index, uint seed) {
    return Rng(uvec4(pixel_index, sample_index, seed, 0u), 0u);
}

// The hash sampler's slot: four independent 32-bit values.
uvec4 hash_slot(Rng rng) {
    return pcg4d(uvec4(rng.key.x, rng.key.y, rng.key.z, rng.dim));
}

// The hash sampler's next number, uniform in [0, 1), whatever render.sampler says
// (the float probe compares it between backends).
float rng_next(INOUT(Rng) rng) {
    uvec4 h = hash_slot(rng);
    rng.dim += 1u;
    return unit_float(h.x);
}

// Laine and Karras' hash that permutes 32-bit values such that each bit depends
// only on the bits below it, with Burley's constants: applied to bit-reversed
// values, it is a random nested uniform (Owen) scramble in base 2 of the binary
// fraction 0.b31 b30 ... b0, keyed by `seed`.
uint laine_karras_permutation(uint x, uint seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

// The second Sobol dimension of index i, bit-reversed. Its generator matrix is
// Pascal's triangle mod 2 (primitive polynomial x + 1): by Lucas' theorem output
// bit l is the parity of the index bits k whose binary digits contain l's, a
// superset sum that five masked shifts compute.
uint sobol_second_reversed(uint i) {
    i ^= (i >> 1u) & 0x55555555u;
    i ^= (i >> 2u) & 0x33333333u;
    i ^= (i >> 4u) & 0x0f0f0f0fu;
    i ^= (i >> 8u) & 0x00ff00ffu;
    i ^= (i >> 16u) & 0x0000ffffu;
    return i;
}

// The sobol sampler's slot: the pixel's sample index shuffled by an Owen scramble
// of its own (which maps each aligned block of 2^k indices onto another, so every
// prefix of 2^k samples is still a whole net), then both dimensions scrambled. The
// first dimension is the index bit-reversed (van der Corput), so its scramble is
// reverse(permutation(index)).
uvec2 sobol_slot(Rng rng) {
    uvec4 seeds = pcg4d(uvec4(rng.key.x, rng.key.z, rng.dim, 0x50b0105u));
    uint index = bitfieldReverse(laine_karras_permutation(bitfieldReverse(rng.key.y), seeds.x));
    uint x = bitfieldReverse(laine_karras_permutation(index, seeds.y));
    uint y = bitfieldReverse(laine_karras_permutation(sobol_second_reversed(index), seeds.z));
    return uvec2(x, y);
}
