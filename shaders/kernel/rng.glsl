// Counter-based random numbers: every value is a pure function of
// (seed, pixel, sample index, dimension), so any split of the sample range over
// runs or machines draws exactly the same numbers (DESIGN.md, principle 4).
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

// A uniform float in [0, 1): the top 24 bits scaled by 2^-24, so 1.0 is never reached
// (the largest value is 1 - 2^-24, exactly representable).
float rng_next(INOUT(Rng) rng) {
    uvec4 h = pcg4d(uvec4(rng.key.x, rng.key.y, rng.key.z, rng.dim));
    rng.dim += 1u;
    return float(h.x >> 8u) * (1.0f / 16777216.0f);
}
