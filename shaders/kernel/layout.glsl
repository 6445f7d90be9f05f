// Buffer layouts shared by the compute shader and the C++ host.
// vec4/uvec4 members only, so GLSL and C++ agree on every offset without padding
// rules to remember (std140 and std430 coincide for such structs), and each member is
// one 16-byte texel of the texel buffers the kernel reads them from;
// host/kernel/types.hpp static_asserts the sizes. Beside each struct,
// Name_FROM_TEXELS(array, i) assembles element i of an array of kernel/arrays.glsl
// from its texels, fetched by the host's fetch_texel(array, t) (render.comp).
// Unused .w lanes are documented as such and written as 0 by the host.

// Each kind of primitive's record, Name and Name_FROM_TEXELS, is in its file
// (shapes/<name>.glsl, the part under SHAPE_RECORDS), included here in the order of
// shapes/kinds.glsl through the list generated from it (cmake/PrimitiveKinds.cmake).
#define SHAPE_RECORDS
#include "shape_files.glsl"
#undef SHAPE_RECORDS

// A material: the fields of kernel/material_fields.glsl, each named for what it
// holds, MATERIAL_TEXELS texels in all. render.comp assembles one from its texels
// (material_from_texels); the host writes it as it is (types.hpp checks the offsets).
const uint MATERIAL_TEXELS = 20u;
struct Material {
#define MATERIAL_FIELD(T, name, texel, lane) T name;
#define MATERIAL_FIELD3(T, name, texel) T name;
#define MATERIAL_PAD(texel, lane) uint pad_##texel##_##lane;
#include "material_fields.glsl"
};

// A texture image (texture.glsl): its texels are in texture_words from info.x on,
// row after row from the top, as the format says; info.y = width, info.z = height,
// info.w = the wrap modes, horizontal in bits 0-1 and vertical in bits 2-3
// (WRAP_REPEAT, _CLAMP, _MIRROR), the format in bits 4-5 (TEXEL_HALF, TEXEL_RGBA8)
// and TEXTURE_SRGB_BIT.
// decode: x = a normal map's scale (normal_map.glsl); y, z, w unused.
struct Texture {
    uvec4 info;
    vec4 decode;
};
#define Texture_FROM_TEXELS(b, i) Texture(fetch_texel(b, 2u * (i)), fetch_vec4(b, 2u * (i) + 1u))

// One of the scene's `lights`: a point, spot or directional light, one record for
// the three kinds so that the kernel loops over one list (lights.glsl).
// position: xyz where a point or spot light is, w = 1. A directional light has
//   w = 0 and xyz the unit vector toward it, against the way its light travels:
//   the point at infinity that way, in homogeneous coordinates.
// radiance: rgb = colour * intensity (for a directional light the irradiance it
//   gives a surface facing it); w unused.
// cone: a spot light's cone, xyz = its unit axis (the way it shines) * s and
//   w = -cos(outer angle) * s, with s = 1 / max(cos(inner) - cos(outer), 0.001):
//   clamp(dot(cone.xyz, -l) + cone.w, 0, 1) is 1 inside the inner cone and 0 outside
//   the outer one. (0, 0, 0, 1) for the other kinds, whose factor is then 1. Fetched
//   only with HAS_DIRECTED_LIGHTS: a scene of point lights never reads it.
struct Light {
    vec4 position;
    vec4 radiance;
    vec4 cone;
};
#define Light_FROM_TEXELS(b, i)                                                \
    Light(fetch_vec4(b, 3u * (i)), fetch_vec4(b, 3u * (i) + 1u),               \
          HAS_DIRECTED_LIGHTS ? fetch_vec4(b, 3u * (i) + 2u) : vec4(0.0f, 0.0f, 0.0f, 1.0f))

// One emissive primitive: a primitive whose material has nonzero emission
// (kernel/emitters.glsl samples them, host/flatten/flat_scene.cpp lists them). Emitters
// are chosen with probability proportional to their power, through the cumulative
// fractions in cdf.x, the last of which is exactly 1.
struct Emitter {
    uvec4 prim;      // x = primitive reference (kind << REF_KIND_SHIFT | index, as the grid's),
                     // y = the part of a cylinder (CYLINDER_SIDE, _BASE_CAP, _TOP_CAP), z/w unused
    vec4 cdf;        // x = power of the emitters up to and including this one / total power,
                     // y = that of the emitters before it (the previous x, 0 for the first), z/w unused
};
#define Emitter_FROM_TEXELS(b, i) Emitter(fetch_texel(b, 2u * (i)), fetch_vec4(b, 2u * (i) + 1u))

// Per-render constants: PARAM_TEXELS texels, each value named in kernel/params.glsl
// and read through its accessor (camera_eye(), max_depth(), ...), never by lane.
// The kinds' counts take the last texels (params.glsl), as many as PRIMITIVE_KINDS need.
const uint PARAM_KIND_TEXEL = 17u;
const uint PARAM_TEXELS = PARAM_KIND_TEXEL + (PRIMITIVE_KINDS + 3u) / 4u;
struct Params {
    uvec4 texels[PARAM_TEXELS];
};
// A value of type T from the bits of its lanes, and back (the accessors' halves).
#define FROM_BITS_uint(bits) (bits)
#define FROM_BITS_uvec3(bits) (bits)
#define FROM_BITS_float(bits) uintBitsToFloat(bits)
#define FROM_BITS_vec3(bits) uintBitsToFloat(bits)
#define TO_BITS_uint(value) (value)
#define TO_BITS_uvec3(value) (value)
#define TO_BITS_float(value) floatBitsToUint(value)
#define TO_BITS_vec3(value) floatBitsToUint(value)

// Per-pixel sums of sample radiance (sums.glsl): each channel's exact sum as a 96-bit
// fixed-point integer in xyz, least significant word first, in units of 2^-40.
// red.w = samples summed, green.w = of those, samples clamped to SUM_SAMPLE_MAX,
// blue.w unused (0). The squares' sums likewise, for the variance (w unused, 0).
struct PixelSum {
    uvec4 red;
    uvec4 green;
    uvec4 blue;
    uvec4 red_squares;
    uvec4 green_squares;
    uvec4 blue_squares;
};

// Per-pixel counters, lanes named in constants.glsl (RAYS_*, WORK_*).
struct Counters {
    uvec4 rays;
    uvec4 work;
    uvec4 tree;
    uvec4 paths;
};

// The render passes of a pixel (HAS_PASSES): over the samples whose eye ray hit a
// surface, the sums of that first hit's base colour (albedo), of its shading normal
// plus one in each component (so that every term is positive: the host subtracts the
// hits again), and of its distance from the eye, each channel summed exactly as the
// radiance is (sums.glsl). The lanes w are unused (0): the counts are the Counters'
// (RAYS_EYE samples, TREE_EYE_HITS of them hits).
struct PassSums {
    uvec4 albedo_red;
    uvec4 albedo_green;
    uvec4 albedo_blue;
    uvec4 normal_x;
    uvec4 normal_y;
    uvec4 normal_z;
    uvec4 depth;
};

// On the device a pixel's output is its PixelSum's texels, then its Counters', then
// with HAS_PASSES its PassSums' (pixel_texels(), render.comp).
const uint PIXEL_SUM_TEXELS = 6u;
const uint PIXEL_TEXELS = 10u;
const uint PASS_TEXELS = 7u;
