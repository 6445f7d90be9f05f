#pragma once
// The kernel's shared constants and buffer layouts (shaders/kernel/), seen from C++.
// GLSL types come from GLM; the layout file is included verbatim, so the host and
// the shader cannot disagree on a field.
#include <cstdint>
#include <glm/glm.hpp>

namespace vkrt::kernel {
using namespace glm;
using uint = std::uint32_t;

#include "kernel/constants.glsl"
#include "kernel/layout.glsl"
// sums.glsl's functions take their in-out arguments by reference, as the Kernel's do.
#define INOUT(T) T&
#define HOST_INLINE inline
#include "kernel/sums.glsl"
#undef HOST_INLINE
#undef INOUT

// Sizes and offsets: vec4 members only, so these hold by construction (one 16-byte
// texel a member); the asserts catch anyone adding a vec3 or a scalar.
static_assert(sizeof(vec4) == 16 && sizeof(uvec4) == 16);
static_assert(sizeof(Sphere) == 32);
static_assert(sizeof(Triangle) == 112);
static_assert(sizeof(Material) == 80);
static_assert(sizeof(PointLight) == 32);
static_assert(sizeof(Ring) == 48);
static_assert(sizeof(Cylinder) == 48);
static_assert(sizeof(Emitter) == 32);
static_assert(sizeof(Params) == 304);
static_assert(offsetof(Params, image) == 96 && offsetof(Params, limits) == 128);
static_assert(offsetof(Params, grid_res) == 208 && offsetof(Params, more_counts) == 224);
static_assert(offsetof(Params, ray_tree) == 240);
static_assert(offsetof(Params, area_lights) == 256 && offsetof(Params, emitter_area) == 272);
static_assert(offsetof(Params, global) == 288);
static_assert(sizeof(Counters) == 64);
static_assert(sizeof(PixelSum) == 48);

inline bool operator==(const Counters& a, const Counters& b) {
    return a.rays == b.rays && a.work == b.work && a.tree == b.tree && a.paths == b.paths;
}
inline bool operator==(const PixelSum& a, const PixelSum& b) {
    return a.red == b.red && a.green == b.green && a.blue == b.blue;
}
inline Counters operator+(const Counters& a, const Counters& b) {
    return {a.rays + b.rays, a.work + b.work, a.tree + b.tree, a.paths + b.paths};
}
}  // namespace vkrt::kernel
