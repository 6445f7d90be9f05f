// The numbers a sample draws, from the sampler render.sampler names (rng.glsl;
// the slot layout of a path is in constants.glsl).

// The next slot as one number, uniform in [0, 1).
float rng_1d(INOUT(Rng) rng) {
    uint bits = sampler_kind() == SAMPLER_SOBOL ? sobol_slot(rng).x : hash_slot(rng).x;
    rng.dim += 1u;
    return unit_float(bits);
}

// The next slot as a pair, uniform in [0, 1)^2.
vec2 rng_2d(INOUT(Rng) rng) {
    uvec4 h = sampler_kind() == SAMPLER_SOBOL ? uvec4(sobol_slot(rng), 0u, 0u) : hash_slot(rng);
    rng.dim += 1u;
    return vec2(unit_float(h.x), unit_float(h.y));
}

// Goes to a given slot, so that what follows draws from it.
void rng_seek(INOUT(Rng) rng, uint slot) {
    rng.dim = slot;
}
