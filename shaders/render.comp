#version 450
// The compute entry point: one invocation renders one sample (pass.x) of one pixel
// and adds it to that pixel's sums. All the maths lives in kernel/, shared with the
// C++ reference renderer.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#ifdef SCENE_BY_ADDRESS
// Built a second time with SCENE_BY_ADDRESS for devices whose bindings cannot hold
// the scene (host/gpu/data_paths.hpp): it is then read through its device address.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneTexels { uvec4 texels[]; };
#endif

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#define INOUT(T) inout T
#define HOT   // the reference backend forces these inline (host/kernel/kernel.hpp)
#define FEATURE(id, name) layout(constant_id = id) const bool name = true;
#include "kernel/features.glsl"
#include "kernel/constants.glsl"
#include "kernel/layout.glsl"
#include "kernel/sums.glsl"

// The descriptor set (render_bindings.glsl). Texel buffers by default: lavapipe
// compiles storage-buffer and uniform loads badly
// (docs/decisions/0001-texel-buffers.md); a device picks the others through the
// device choices.
#define TEXEL_BINDING(binding_, name, format, access) \
    layout(binding = binding_, format) uniform access uimageBuffer name;
#define STORAGE_BINDING(binding_, name, access) \
    layout(std430, binding = binding_) access buffer name##_block { uvec4 texels[]; } name;
#define UNIFORM_BINDING(binding_, name) \
    layout(std140, binding = binding_) uniform name##_block { uvec4 texels[PARAM_TEXELS]; } name;
#define DEVICE_CHOICE(id, name) layout(constant_id = id) const bool name = false;
#include "render_bindings.glsl"
// pass: x = sample index; y, z = the tile's first pixel column and row; w = the
// first row of the slab of rows the pixel buffer holds. bases: where each array of
// kernel/arrays.glsl starts in the scene buffer (host/gpu/scene_pack.hpp), by id,
// and after the last the texel where its r32ui arrays start. Push constants rather
// than params: they describe the device's packing, not the render. scene_address.xy:
// the scene buffer's device address, low word first, when it is read by address.
layout(push_constant) uniform PassBlock {
    uvec4 pass;
    uvec4 bases[4];
    uvec4 scene_address;
};
// Copied by main(), like the params: read from push constants in the loops, they
// took 1.14x the time on lavapipe (ten_spheres, 512x512, 32 spp).
uvec4 g_bases[4];
#define SCENE_ARRAY(id, name, Element, load, format) \
    uint name##_base() { return g_bases[id / 4][id % 4]; }
#include "kernel/arrays.glsl"
const uint SCENE_ARRAYS = 0u
#define SCENE_ARRAY(id, name, Element, load, format) + 1u
#include "kernel/arrays.glsl"
    ;
uint scene_words_start() { return g_bases[SCENE_ARRAYS / 4u][SCENE_ARRAYS % 4u]; }

// Read once per invocation by main().
Params params;

#ifdef SCENE_BY_ADDRESS
SceneTexels g_scene;  // set by main()
#endif

// Texel t of the scene buffer, and word w of its r32ui arrays.
uvec4 scene_texel(uint t) {
#ifdef SCENE_BY_ADDRESS
    return g_scene.texels[t];
#else
    if (SCENE_IN_STORAGE_BUFFERS) {
        return scene_storage.texels[t];
    }
    return imageLoad(scene_texels, int(t));
#endif
}

uint scene_word(uint w) {
#ifdef SCENE_BY_ADDRESS
    const uint i = scene_words_start() * 4u + w;
    return g_scene.texels[i >> 2u][i & 3u];
#else
    if (SCENE_IN_STORAGE_BUFFERS) {
        const uint i = scene_words_start() * 4u + w;
        return scene_storage.texels[i >> 2u][i & 3u];
    }
    return imageLoad(scene_words, int(w)).x;
#endif
}

uvec4 load_pixel_texel(uint t) {
    if (SCENE_IN_STORAGE_BUFFERS) {
        return pixel_storage.texels[t];
    }
    return imageLoad(pixel_texels, int(t));
}

void store_pixel_texel(uint t, uvec4 value) {
    if (SCENE_IN_STORAGE_BUFFERS) {
        pixel_storage.texels[t] = value;
    } else {
        imageStore(pixel_texels, int(t), value);
    }
}

// Element i of a scene array (loads.glsl): its texels from the array's base on.
#define fetch_texel(array, t) scene_texel(array##_base() + (t))
#define fetch_vec4(array, t) uintBitsToFloat(fetch_texel(array, t))
#define uint_FROM_TEXELS(array, i) scene_word(array##_base() + (i))
#define LOAD_ELEMENT(Element, name, i) Element##_FROM_TEXELS(name, i)
// The kernel's invariants are checked by the reference backend (host/kernel/checks.hpp).
#define CHECK(condition)

// A material from its texels, field by field (kernel/material_fields.glsl): each
// texel fetched once into t<texel>, whichever fields it holds. Without a loop or an
// array, so that the driver drops a texel no field of the pipeline reads without
// having to unroll anything first. A field in a texel beyond t19 fails to compile
// here: add its fetch.
Material material_from_texels(uint i) {
    uint first = MATERIAL_TEXELS * i;
    uvec4 t0 = fetch_texel(materials, first), t1 = fetch_texel(materials, first + 1u),
          t2 = fetch_texel(materials, first + 2u), t3 = fetch_texel(materials, first + 3u),
          t4 = fetch_texel(materials, first + 4u), t5 = fetch_texel(materials, first + 5u),
          t6 = fetch_texel(materials, first + 6u), t7 = fetch_texel(materials, first + 7u),
          t8 = fetch_texel(materials, first + 8u), t9 = fetch_texel(materials, first + 9u),
          t10 = fetch_texel(materials, first + 10u), t11 = fetch_texel(materials, first + 11u),
          t12 = fetch_texel(materials, first + 12u), t13 = fetch_texel(materials, first + 13u),
          t14 = fetch_texel(materials, first + 14u), t15 = fetch_texel(materials, first + 15u),
          t16 = fetch_texel(materials, first + 16u), t17 = fetch_texel(materials, first + 17u),
          t18 = fetch_texel(materials, first + 18u), t19 = fetch_texel(materials, first + 19u);
    Material m;
#define MATERIAL_FIELD(T, name, texel, lane) m.name = FROM_BITS_##T(t##texel.lane);
#define MATERIAL_FIELD3(T, name, texel) m.name = FROM_BITS_##T(t##texel.xyz);
#define MATERIAL_PAD(texel, lane) m.pad_##texel##_##lane = t##texel.lane;
#include "kernel/material_fields.glsl"
    return m;
}
#define Material_FROM_TEXELS(b, i) material_from_texels(i)

#include "kernel/all.glsl"

void main() {
    // Unrolled, so that every accessor reads a register: a loop the driver keeps
    // would index `params` at run time and put it in memory.
    [[unroll]] for (uint i = 0u; i < PARAM_TEXELS; ++i) {
        params.texels[i] = PARAMS_IN_UNIFORM_BUFFER ? params_uniform.texels[i] : imageLoad(params_texels, int(i));
    }
    g_bases = bases;
#ifdef SCENE_BY_ADDRESS
    g_scene = SceneTexels(scene_address.xy);
#endif
    // Each row of 8 invocations renders a 4x2 block of pixels, not a row of 8: an
    // 8-lane SIMD vector then traces rays that agree more often on where they go
    // (docs/decisions/0017-loop-shapes-for-simd.md). Only which invocation renders
    // which pixel changes; every pixel's sample is the same.
    uint row = gl_LocalInvocationID.y;
    uint lane = gl_LocalInvocationID.x;
    uint px = pass.y + gl_WorkGroupID.x * 8u + (row & 1u) * 4u + (lane & 3u);
    uint py = pass.z + gl_WorkGroupID.y * 8u + (row >> 1u) * 2u + (lane >> 2u);
    if (px >= image_width() || py >= image_height()) {
        return;
    }
    // A pixel's texels: its sums, its counters, and with HAS_PASSES its render passes.
    uint stride = HAS_PASSES ? PIXEL_TEXELS + PASS_TEXELS : PIXEL_TEXELS;
    uint first = ((py - pass.w) * image_width() + px) * stride;
    // The squares' texels only where the render keeps them (HAS_SQUARES).
    PixelSum sum = PixelSum(load_pixel_texel(first), load_pixel_texel(first + 1u), load_pixel_texel(first + 2u),
                            uvec4(0u), uvec4(0u), uvec4(0u));
    if (HAS_SQUARES) {
        sum.red_squares = load_pixel_texel(first + 3u);
        sum.green_squares = load_pixel_texel(first + 4u);
        sum.blue_squares = load_pixel_texel(first + 5u);
    }
    uint c = first + PIXEL_SUM_TEXELS;
    Counters counts = Counters(load_pixel_texel(c), load_pixel_texel(c + 1u), load_pixel_texel(c + 2u),
                               load_pixel_texel(c + 3u));
    SampleResult result = render_sample(px, py, pass.x);
    accumulate_sample(result, sum, counts);
    if (HAS_PASSES) {
        uint t = first + PIXEL_TEXELS;
        PassSums passes = PassSums(load_pixel_texel(t), load_pixel_texel(t + 1u), load_pixel_texel(t + 2u),
                                   load_pixel_texel(t + 3u), load_pixel_texel(t + 4u), load_pixel_texel(t + 5u),
                                   load_pixel_texel(t + 6u));
        accumulate_passes(result, passes);
        store_pixel_texel(t, passes.albedo_red);
        store_pixel_texel(t + 1u, passes.albedo_green);
        store_pixel_texel(t + 2u, passes.albedo_blue);
        store_pixel_texel(t + 3u, passes.normal_x);
        store_pixel_texel(t + 4u, passes.normal_y);
        store_pixel_texel(t + 5u, passes.normal_z);
        store_pixel_texel(t + 6u, passes.depth);
    }
    store_pixel_texel(first, sum.red);
    store_pixel_texel(first + 1u, sum.green);
    store_pixel_texel(first + 2u, sum.blue);
    if (HAS_SQUARES) {
        store_pixel_texel(first + 3u, sum.red_squares);
        store_pixel_texel(first + 4u, sum.green_squares);
        store_pixel_texel(first + 5u, sum.blue_squares);
    }
    store_pixel_texel(c, counts.rays);
    store_pixel_texel(c + 1u, counts.work);
    store_pixel_texel(c + 2u, counts.tree);
    store_pixel_texel(c + 3u, counts.paths);
}
