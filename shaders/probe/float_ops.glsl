// One probe operation (float_op_ids.glsl) applied to one argument; the result in x,
// or in x, y, z for vectors. The same text is the GLSL of float_probe.comp and the
// C++ of host/probe/cpu_float_probe.cpp, so the columns of `vkrt devices
// --float-profile` differ only by the compilers and the maths libraries.
// Every input comes from a buffer at run time: a constant argument would be folded by
// the compiler on the build machine, and the probe would measure that instead.

// A function of its own, as hit_point (global.glsl) is: `precise` is kept to a local
// declared outside any switch or loop.
float product_sum_precise(float x, float y, float z) {
    precise float r = x * y + z;
    return r;
}

// The kernel's random number of stream `key` at dimension `dim`.
float random_number(uvec4 key, uint dim) {
    Rng rng = Rng(uvec4(key.y, key.z, key.w, 0u), dim);
    return rng_next(rng);
}

// op.x is the FLOAT_OP_ number; op.yzw carry integer arguments (FLOAT_OP_RNG).
vec4 float_op(uvec4 op, vec4 a) {
    vec3 v = vec3(a.x, a.y, a.z);
    switch (op.x) {
    case FLOAT_OP_PRODUCT_SUM: return vec4(a.x * a.y + a.z, 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_PRODUCT_SUM_PRECISE: return vec4(product_sum_precise(a.x, a.y, a.z), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_MUL: return vec4(a.x * a.y, 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_ADD: return vec4(a.x + a.y, 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_DIV: return vec4(a.x / a.y, 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_POW: return vec4(pow(a.x, a.y), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_SQRT: return vec4(sqrt(a.x), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_INVERSESQRT: return vec4(inversesqrt(a.x), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_NORMALIZE: return vec4(normalize(v), 0.0f);
    case FLOAT_OP_LENGTH: return vec4(length(v), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_UNIT_VECTOR: return vec4(unit_vector(v), 0.0f);
    case FLOAT_OP_EXP2: return vec4(exp2(a.x), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_LOG2: return vec4(log2(a.x), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_SIN: return vec4(sin(a.x), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_COS: return vec4(cos(a.x), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_MIN: return vec4(min(a.x, a.y), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_MAX: return vec4(max(a.x, a.y), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_RNG: return vec4(random_number(op, uint(a.x)), 0.0f, 0.0f, 0.0f);
    case FLOAT_OP_CLASSIFY: return vec4(isnan(a.x) ? 1.0f : 0.0f, isinf(a.x) ? 1.0f : 0.0f, 0.0f, 0.0f);
    default: return vec4(0.0f);
    }
}
