// The operations of the float probe, by number: the host lists (operation, argument)
// cases and both sides, shaders/float_probe.comp on a Vulkan device and
// host/probe/cpu_float_probe.cpp on the CPU, apply float_op (float_ops.glsl) to each.
// Shared so that the numbers cannot drift apart.
const uint FLOAT_OP_PRODUCT_SUM = 0u;          // x * y + z as the compiler pleases
const uint FLOAT_OP_PRODUCT_SUM_PRECISE = 1u;  // x * y + z under `precise`
const uint FLOAT_OP_MUL = 2u;                  // x * y
const uint FLOAT_OP_ADD = 3u;                  // x + y
const uint FLOAT_OP_DIV = 4u;                  // x / y
const uint FLOAT_OP_POW = 5u;                  // pow(x, y)
const uint FLOAT_OP_SQRT = 6u;
const uint FLOAT_OP_INVERSESQRT = 7u;
const uint FLOAT_OP_NORMALIZE = 8u;            // of (x, y, z), into (x, y, z)
const uint FLOAT_OP_LENGTH = 9u;               // of (x, y, z)
const uint FLOAT_OP_UNIT_VECTOR = 10u;         // the kernel's (ray.glsl), of (x, y, z)
const uint FLOAT_OP_EXP2 = 11u;
const uint FLOAT_OP_LOG2 = 12u;
const uint FLOAT_OP_SIN = 13u;
const uint FLOAT_OP_COS = 14u;
const uint FLOAT_OP_MIN = 15u;                 // min(x, y)
const uint FLOAT_OP_MAX = 16u;                 // max(x, y)
const uint FLOAT_OP_CLASSIFY = 17u;            // (isnan(x), isinf(x)) as 1 or 0
const uint FLOAT_OP_RNG = 18u;                 // rng_next (rng.glsl) of the stream
                                               // (pixel, sample, seed) = op.yzw at
                                               // dimension x
