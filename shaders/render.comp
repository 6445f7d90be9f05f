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

// Binding numbers are mirrored in host/gpu/vulkan_pipeline.hpp (enum Binding).
// Every binding is a storage texel buffer, an imageBuffer of 16-byte texels (one
// uvec4/vec4 per struct member; the grid's two arrays are r32ui), the scene's read-only:
// - Not SSBOs: lavapipe (Mesa 22.3) turns every SSBO load or store into a scalar loop
//   over the 8 SIMD lanes with a bounds check and a stack round-trip per component,
//   which made the primitive loops ~10x slower than the C++ reference. Image loads
//   and stores are vector gathers and scatters, compiled inline.
// - Not uniform texel buffers (texelFetch on a usamplerBuffer), as the scene was read
//   until 2026-12-02: lavapipe compiles a texel fetch from any format but 8-bit RGBA
//   into a call to a sampling function of its own, and every vector register live
//   across the call is spilled to the stack and read back. Each sphere test and each
//   grid cell paid that. With image loads, image H renders 1.03x faster on lavapipe
//   and SPD balls by brute force 1.1x, same images (docs/grid.md, "Image loads").
// - Not a uniform buffer for the params either: lavapipe inlines uniform-buffer values
//   that decide a branch or a loop into the shader and compiles that variant when a
//   dispatch is recorded after the pipeline or descriptors were bound, every time (no
//   cache of variants in 22.3). That put an LLVM compile, or a load from Mesa's disk
//   cache, into every submission: image H rendered in 2.1 s instead of 0.43 s with the
//   disk cache off, 0.21 s instead of 0.14 s with it on (docs/grid.md). Read from a
//   texel buffer once per invocation, the params are values the compiler cannot see
//   and the pipeline is compiled once, when it is created. The push constants (sample
//   and band) are uniform-buffer values to lavapipe too, so they must not decide a
//   branch by themselves. vulkan_backend_test checks that no uniform buffer is declared.
// Storage texel buffers count against a device's storage-image limits, whose
// guaranteed minimum is 4: device selection (gpu/vulkan_devices.cpp) asks for one per
// binding.
layout(binding = 0, rgba32ui) uniform readonly uimageBuffer params_texels;      // 19 texels: one Params
Params params;   // set by main() before anything reads it
layout(binding = 1, rgba32ui) uniform readonly uimageBuffer material_texels;    // 5 texels per Material
layout(binding = 2, rgba32ui) uniform readonly uimageBuffer sphere_texels;      // 2 texels per Sphere
layout(binding = 3, rgba32ui) uniform readonly uimageBuffer triangle_texels;    // 7 texels per Triangle
layout(binding = 4, rgba32ui) uniform readonly uimageBuffer light_texels;       // 2 texels per PointLight
layout(binding = 5, rgba32ui) uniform uimageBuffer sums;       // 3 texels per pixel (PixelSum)
layout(binding = 6, rgba32ui) uniform uimageBuffer counters;   // 4 texels per pixel (Counters)
layout(binding = 7, r32ui) uniform readonly uimageBuffer grid_cell_starts;    // r32ui, cells + 1 entries
layout(binding = 8, r32ui) uniform readonly uimageBuffer grid_refs;           // r32ui, one per reference
layout(binding = 9, rgba32ui) uniform readonly uimageBuffer ring_texels;         // 3 texels per Ring
layout(binding = 10, rgba32ui) uniform readonly uimageBuffer cylinder_texels;    // 3 texels per Cylinder
layout(binding = 11, rgba32ui) uniform readonly uimageBuffer emitter_texels;     // 2 texels per Emitter
layout(binding = 12, rgba32ui) uniform readonly uimageBuffer grid_sphere_texels; // 1 texel per grid reference
layout(push_constant) uniform PassBlock { uvec4 pass; };   // x = sample index, y = first row of the band

// The buffer accessors the kernel calls (host/ref/kernel.hpp has the C++ ones). Fields
// a caller does not use are dropped by the driver's dead-code elimination. A macro, not a
// function: an image parameter would lose the format that imageLoad needs.
#define fetch_vec4(b, i) uintBitsToFloat(imageLoad(b, int(i)))
Material load_material(uint i) {
    uint b = 5u * i;
    return Material(fetch_vec4(material_texels, b), fetch_vec4(material_texels, b + 1u),
                    fetch_vec4(material_texels, b + 2u), fetch_vec4(material_texels, b + 3u),
                    fetch_vec4(material_texels, b + 4u));
}
Sphere load_sphere(uint i) {
    return Sphere(fetch_vec4(sphere_texels, 2u * i), imageLoad(sphere_texels, int(2u * i + 1u)));
}
Triangle load_triangle(uint i) {
    uint b = 7u * i;
    return Triangle(fetch_vec4(triangle_texels, b), fetch_vec4(triangle_texels, b + 1u),
                    fetch_vec4(triangle_texels, b + 2u), fetch_vec4(triangle_texels, b + 3u),
                    fetch_vec4(triangle_texels, b + 4u), fetch_vec4(triangle_texels, b + 5u),
                    imageLoad(triangle_texels, int(b + 6u)));
}
PointLight load_light(uint i) {
    return PointLight(fetch_vec4(light_texels, 2u * i), fetch_vec4(light_texels, 2u * i + 1u));
}
Ring load_ring(uint i) {
    uint b = 3u * i;
    return Ring(fetch_vec4(ring_texels, b), fetch_vec4(ring_texels, b + 1u), imageLoad(ring_texels, int(b + 2u)));
}
Cylinder load_cylinder(uint i) {
    uint b = 3u * i;
    return Cylinder(fetch_vec4(cylinder_texels, b), fetch_vec4(cylinder_texels, b + 1u),
                    imageLoad(cylinder_texels, int(b + 2u)));
}
Emitter load_emitter(uint i) {
    return Emitter(imageLoad(emitter_texels, int(2u * i)), fetch_vec4(emitter_texels, 2u * i + 1u));
}
// The Params struct, member by member (layout.glsl).
Params load_params() {
    return Params(fetch_vec4(params_texels, 0u),
                  fetch_vec4(params_texels, 1u),
                  fetch_vec4(params_texels, 2u),
                  fetch_vec4(params_texels, 3u),
                  fetch_vec4(params_texels, 4u),
                  fetch_vec4(params_texels, 5u),
                  imageLoad(params_texels, 6),
                  imageLoad(params_texels, 7),
                  imageLoad(params_texels, 8),
                  fetch_vec4(params_texels, 9u),
                  fetch_vec4(params_texels, 10u),
                  fetch_vec4(params_texels, 11u),
                  fetch_vec4(params_texels, 12u),
                  imageLoad(params_texels, 13),
                  imageLoad(params_texels, 14),
                  fetch_vec4(params_texels, 15u),
                  imageLoad(params_texels, 16),
                  fetch_vec4(params_texels, 17u),
                  imageLoad(params_texels, 18));
}
uint load_cell_start(uint i) { return imageLoad(grid_cell_starts, int(i)).x; }
uint load_ref(uint i) { return imageLoad(grid_refs, int(i)).x; }
// The center and radius of sphere `index`, listed at `position` in the grid's
// references: read from the copy the host keeps beside the references
// (gpu/grid_spheres.hpp), at `position`, rather than from the sphere array at `index`.
// Both reads are gathers here; from the sphere array the sphere's had to wait for the
// reference's, and a cell's spheres lay scattered instead of in consecutive texels.
// Image H rendered 1.16x faster on lavapipe, a million spheres 1.11x (docs/grid.md,
// "Spheres beside their references"). The C++ reference reads the sphere array, which
// is faster there.
vec4 load_grid_sphere(uint position, uint index) { return fetch_vec4(grid_sphere_texels, position); }

#include "kernel/all.glsl"

void main() {
    params = load_params();
    // Each row of the 8x8 workgroup renders a 4x2 block of its 8x8 pixels rather than
    // a row of 8. lavapipe packs one row of invocations into one 8-lane SIMD vector,
    // which walks the grid until its last lane is done; rays from a squarer patch of
    // pixels agree more often on where they go and when they stop (image H 1.08x, SPD
    // balls 1.07x faster on lavapipe, median of 9 and 5 renders). Only which
    // invocation renders which pixel changes: every pixel's sample is the same.
    uint row = gl_LocalInvocationID.y;
    uint lane = gl_LocalInvocationID.x;
    uint px = gl_WorkGroupID.x * 8u + (row & 1u) * 4u + (lane & 3u);
    uint py = gl_WorkGroupID.y * 8u + (row >> 1u) * 2u + (lane >> 2u) + pass.y;
    if (px >= params.image.x || py >= params.image.y) {
        return;
    }
    uint index = py * params.image.x + px;
    PixelSum sum = PixelSum(imageLoad(sums, int(3u * index)), imageLoad(sums, int(3u * index + 1u)),
                            imageLoad(sums, int(3u * index + 2u)));
    Counters counts = Counters(imageLoad(counters, int(4u * index)), imageLoad(counters, int(4u * index + 1u)),
                               imageLoad(counters, int(4u * index + 2u)), imageLoad(counters, int(4u * index + 3u)));
    accumulate_sample(render_sample(px, py, pass.x), sum, counts);
    imageStore(sums, int(3u * index), sum.red);
    imageStore(sums, int(3u * index + 1u), sum.green);
    imageStore(sums, int(3u * index + 2u), sum.blue);
    imageStore(counters, int(4u * index), counts.rays);
    imageStore(counters, int(4u * index + 1u), counts.work);
    imageStore(counters, int(4u * index + 2u), counts.tree);
    imageStore(counters, int(4u * index + 3u), counts.paths);
}
