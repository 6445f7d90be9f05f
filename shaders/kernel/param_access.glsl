// The kernel's accessors of the per-render constants, one per value of
// kernel/params.glsl: camera_eye(), max_depth(), ... each reads its lanes of `params`,
// which the host fills before the kernel runs.
#define PARAM(T, name, texel, lane) \
    T name() { return FROM_BITS_##T(params.texels[texel].lane); }
#define PARAM3(T, name, texel) \
    T name() { return FROM_BITS_##T(uvec3(params.texels[texel])); }
#include "params.glsl"
