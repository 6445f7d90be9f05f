// Counter-based random numbers: every value is a pure function of
// (seed, pixel, sample index, dimension), so any split of the sample range over
// runs or machines draws exactly the same numbers (docs/architecture.md, principle 4).
// The mixing function is pcg4d from Jarzynski & Olano, "Hash Functions for GPU
// Rendering" (JCGT 2020): an LCG step on each lane, then two rounds of cross-lane
// multiply-adds around an xorshift. It is integer-only, so both backends agree bit
// for bit.

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

// The stream of one sample of one pixel; `dim` counts the numbers drawn so far.
struct Rng {
    uvec4 key;
    uint dim;
};

Rng rng_start(uint pixel_index, uint sample_index, uint seed) {
    return Rng(uvec4(pixel_index, sample_index, seed, 0u), 0u);
}

// A hash's top 24 bits as a float in [0, 1), scaled by 2^-24: every one of them is
// exactly a float, so the conversion does not round, and 1.0 is never reached (the
// largest value is 1 - 2^-24). Converting all 32 bits would round the top 128 values
// of 2^32 up to exactly 1.0, and a sampler given u = 1 picks past its last bin.
float unit_float(uint bits) {
    return float(bits >> 8u) * (1.0f / 16777216.0f);
}

// The next number of the stream, uniform in [0, 1).
float rng_next(INOUT(Rng) rng) {
    uvec4 h = pcg4d(uvec4(rng.key.x, rng.key.y, rng.key.z, rng.dim));
    rng.dim += 1u;
    return unit_float(h.x);
}
