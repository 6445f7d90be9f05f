#version 450
// The float probe of `vkrt devices --float-profile`: one invocation applies one
// operation to one argument (probe/float_ops.glsl). Storage buffers, not the texel
// buffers render.comp needs for speed: a few thousand cases run in milliseconds.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "kernel/constants.glsl"
#define INOUT(T) inout T
uint offset_shrink() { return 0u; }  // ray.glsl's one parameter (kernel/params.glsl), unused here
#include "kernel/ray.glsl"  // unit_vector, measured as the kernel uses it
#include "kernel/rng.glsl"  // rng_next, compared bit for bit with the CPU's
#include "probe/float_op_ids.glsl"
#include "probe/float_ops.glsl"

// Mirrored by vkrt::probe::ProbeCase (host/probe/float_cases.hpp).
struct ProbeCase {
    vec4 arg;
    uvec4 op;  // x: a FLOAT_OP_ number
};
layout(std430, binding = 0) readonly buffer Cases { ProbeCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(cases.length())) {
        return;
    }
    results[i] = float_op(cases[i].op, cases[i].arg);
}
