#version 450
// The compute entry point: one invocation renders one sample (pass.x) of one pixel
// and adds it to that pixel's sums. All the maths lives in kernel/, shared with the
// C++ reference renderer.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#define INOUT(T) inout T
#define FEATURE(id, name) layout(constant_id = id) const bool name = true;
#include "kernel/features.glsl"
#include "kernel/constants.glsl"
#include "kernel/layout.glsl"

// Binding numbers are mirrored in host/gpu/vulkan_backend.cpp (enum Binding).
layout(std140, binding = 0) uniform ParamsBlock { Params params; };
layout(std430, binding = 1) readonly buffer MaterialBuffer { Material materials[]; };
layout(std430, binding = 2) readonly buffer SphereBuffer { Sphere spheres[]; };
layout(std430, binding = 3) readonly buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, binding = 4) readonly buffer LightBuffer { PointLight lights[]; };
layout(std430, binding = 5) buffer AccumBuffer { vec4 accum[]; };
layout(std430, binding = 6) buffer CounterBuffer { uvec4 counters[]; };
layout(push_constant) uniform PassBlock { uvec4 pass; };   // x = sample index

#include "kernel/all.glsl"

void main() {
    uint px = gl_GlobalInvocationID.x;
    uint py = gl_GlobalInvocationID.y;
    if (px >= params.image.x || py >= params.image.y) {
        return;
    }
    uint index = py * params.image.x + px;
    vec4 sums = accum[index];
    uvec4 counts = counters[index];
    accumulate_sample(render_sample(px, py, pass.x), sums, counts);
    accum[index] = sums;
    counters[index] = counts;
}
