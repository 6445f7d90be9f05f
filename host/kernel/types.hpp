#pragma once
// The kernel's shared constants and buffer layouts (shaders/kernel/), seen from C++.
// GLSL types come from GLM; the layout file is included verbatim, so the host and
// the shader cannot disagree on a field.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <glm/glm.hpp>

namespace vkrt::kernel {
using namespace glm;
using uint = std::uint32_t;

#include "kernel/constants.glsl"
#include "kernel/layout.glsl"
// sums.glsl's functions take their in-out arguments by reference, as the Kernel's do.
#define INOUT(T) T&
#define HOST_INLINE inline
#define precise
#include "kernel/sums.glsl"
#undef precise
#undef HOST_INLINE
#undef INOUT

// Sizes and offsets: vec4 members only, so these hold by construction (one 16-byte
// texel a member); the asserts catch anyone adding a vec3 or a scalar.
static_assert(sizeof(vec4) == 16 && sizeof(uvec4) == 16);
static_assert(sizeof(Texture) == 32);
static_assert(sizeof(Light) == 48);
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    static_assert(sizeof(Name) % 16 == 0, "shapes/" #name ".glsl: a record is whole texels");
#include "kernel/shapes/kinds.glsl"

// The kinds of shapes/kinds.glsl are numbered 0, 1, 2, ... in order, and leave kind 7
// to REF_NONE.
namespace kind_table {
constexpr uint kIds[] = {
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) ID,
#include "kernel/shapes/kinds.glsl"
};
consteval bool ids_in_order() {
    for (uint i = 0; i < std::size(kIds); ++i) {
        if (kIds[i] != i) return false;
    }
    return true;
}
static_assert(ids_in_order(), "shapes/kinds.glsl: the kinds' ids must run 0, 1, 2, ... in order");
static_assert(PRIMITIVE_KINDS < (REF_NONE >> REF_KIND_SHIFT), "shapes/kinds.glsl: at most 7 kinds (kind 7 is REF_NONE)");
}  // namespace kind_table
static_assert(sizeof(Emitter) == 32);
static_assert(sizeof(Params) == 16 * PARAM_TEXELS);
static_assert(sizeof(Counters) == 64);
static_assert(sizeof(PixelSum) == 96);
static_assert(sizeof(PixelSum) == 16 * PIXEL_SUM_TEXELS && sizeof(PixelSum) + sizeof(Counters) == 16 * PIXEL_TEXELS);
static_assert(sizeof(PassSums) == 16 * PASS_TEXELS);

// The host's accessors of the per-render constants (kernel/params.glsl): name(params)
// reads a value, set_name(params, value) writes it.
#define PARAM(T, name, texel, lane)                                                                   \
    inline T name(const Params& p) { return FROM_BITS_##T(p.texels[texel].lane); }               \
    inline void set_##name(Params& p, T value) { p.texels[texel].lane = TO_BITS_##T(value); }
#define PARAM3(T, name, texel)                                                                        \
    inline T name(const Params& p) { return FROM_BITS_##T(uvec3(p.texels[texel])); }             \
    inline void set_##name(Params& p, T value) { p.texels[texel] = uvec4(TO_BITS_##T(value), p.texels[texel].w); }
#include "kernel/params.glsl"

// No two values of params.glsl share a lane, and every lane lies inside Params.
namespace param_table {
struct Lane {
    uint texel, lane;
};
constexpr uint x = 0, y = 1, z = 2, w = 3;
constexpr Lane kLanes[] = {
#define PARAM(T, name, texel, lane) {texel, lane},
#define PARAM3(T, name, texel) {texel, x}, {texel, y}, {texel, z},
#include "kernel/params.glsl"
};
consteval bool lanes_distinct_and_inside() {
    for (std::size_t i = 0; i < std::size(kLanes); ++i) {
        if (kLanes[i].texel >= PARAM_TEXELS) return false;
        for (std::size_t j = 0; j < i; ++j) {
            if (kLanes[i].texel == kLanes[j].texel && kLanes[i].lane == kLanes[j].lane) return false;
        }
    }
    return true;
}
static_assert(lanes_distinct_and_inside(), "kernel/params.glsl: two values share a lane, or a texel is out of range");
}  // namespace param_table

// Each field of kernel/material_fields.glsl sits at its texel and lane, and the
// record is MATERIAL_TEXELS texels: the host writes the very bytes render.comp reads.
namespace material_table {
constexpr uint x = 0, y = 1, z = 2, w = 3;
#define MATERIAL_FIELD(T, name, texel, lane) \
    static_assert(offsetof(Material, name) == 16u * (texel) + 4u * (lane), "material_fields.glsl: " #name " is out of place");
#define MATERIAL_FIELD3(T, name, texel) MATERIAL_FIELD(T, name, texel, x)
#define MATERIAL_PAD(texel, lane) MATERIAL_FIELD(uint, pad_##texel##_##lane, texel, lane)
#include "kernel/material_fields.glsl"
}  // namespace material_table
static_assert(sizeof(Material) == 16 * MATERIAL_TEXELS);

inline bool operator==(const Counters& a, const Counters& b) {
    return a.rays == b.rays && a.work == b.work && a.tree == b.tree && a.paths == b.paths;
}
inline bool operator==(const PixelSum& a, const PixelSum& b) {
    return a.red == b.red && a.green == b.green && a.blue == b.blue && a.red_squares == b.red_squares &&
           a.green_squares == b.green_squares && a.blue_squares == b.blue_squares;
}
inline bool operator==(const PassSums& a, const PassSums& b) {
    return a.albedo_red == b.albedo_red && a.albedo_green == b.albedo_green && a.albedo_blue == b.albedo_blue &&
           a.normal_x == b.normal_x && a.normal_y == b.normal_y && a.normal_z == b.normal_z && a.depth == b.depth;
}
inline Counters operator+(const Counters& a, const Counters& b) {
    return {a.rays + b.rays, a.work + b.work, a.tree + b.tree, a.paths + b.paths};
}
}  // namespace vkrt::kernel
