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
#include "kernel/sums.glsl"

// The buffers (kernel/bindings.glsl): storage texel buffers, the scene's read only.
// Not storage or uniform buffers: docs/decisions/0001-texel-buffers.md has the
// measurements. Storage texel buffers count against a device's storage-image limits,
// whose guaranteed minimum is 4: device selection (gpu/vulkan_devices.cpp) asks for
// one per binding.
#define PARAMS_BUFFER(binding_, name) \
    layout(binding = binding_, rgba32ui) uniform readonly uimageBuffer name##_texels;
#define SCENE_BUFFER(binding_, name, Element, load, format) \
    layout(binding = binding_, format) uniform readonly uimageBuffer name##_texels;
#define OUTPUT_BUFFER(binding_, name, Element, format) \
    layout(binding = binding_, format) uniform uimageBuffer name##_texels;
#include "kernel/bindings.glsl"
layout(push_constant) uniform PassBlock { uvec4 pass; };   // x = sample index, y = first row of the band

// Read once per invocation by main(), from a texel buffer rather than a uniform
// buffer, so that no driver folds its values into the shader and compiles a variant
// per dispatch (docs/decisions/0001-texel-buffers.md).
Params params;
// Element i of a scene buffer, from the texels of its image (loads.glsl). Macros, not
// functions: an image parameter would lose the format imageLoad needs.
#define fetch_texel(buffer, i) imageLoad(buffer, int(i))
#define fetch_vec4(buffer, i) uintBitsToFloat(fetch_texel(buffer, i))
#define uint_FROM_TEXELS(buffer, i) imageLoad(buffer, int(i)).x
#define LOAD_ELEMENT(Element, name, i) Element##_FROM_TEXELS(name##_texels, i)

#include "kernel/all.glsl"

void main() {
    for (uint i = 0u; i < PARAM_TEXELS; ++i) {
        params.texels[i] = imageLoad(params_texels, int(i));
    }
    // Each row of 8 invocations renders a 4x2 block of pixels, not a row of 8: an
    // 8-lane SIMD vector then traces rays that agree more often on where they go
    // (docs/decisions/0017-loop-shapes-for-simd.md). Only which invocation renders
    // which pixel changes; every pixel's sample is the same.
    uint row = gl_LocalInvocationID.y;
    uint lane = gl_LocalInvocationID.x;
    uint px = gl_WorkGroupID.x * 8u + (row & 1u) * 4u + (lane & 3u);
    uint py = gl_WorkGroupID.y * 8u + (row >> 1u) * 2u + (lane >> 2u) + pass.y;
    if (px >= image_width() || py >= image_height()) {
        return;
    }
    uint index = py * image_width() + px;
    PixelSum sum = PixelSum(fetch_texel(sums_texels, 3u * index), fetch_texel(sums_texels, 3u * index + 1u),
                            fetch_texel(sums_texels, 3u * index + 2u));
    Counters counts = Counters(fetch_texel(counters_texels, 4u * index), fetch_texel(counters_texels, 4u * index + 1u),
                               fetch_texel(counters_texels, 4u * index + 2u),
                               fetch_texel(counters_texels, 4u * index + 3u));
    accumulate_sample(render_sample(px, py, pass.x), sum, counts);
    imageStore(sums_texels, int(3u * index), sum.red);
    imageStore(sums_texels, int(3u * index + 1u), sum.green);
    imageStore(sums_texels, int(3u * index + 2u), sum.blue);
    imageStore(counters_texels, int(4u * index), counts.rays);
    imageStore(counters_texels, int(4u * index + 1u), counts.work);
    imageStore(counters_texels, int(4u * index + 2u), counts.tree);
    imageStore(counters_texels, int(4u * index + 3u), counts.paths);
}
