// The per-render constants of shaders/kernel/params.glsl: each value has lanes of its
// own, the host's set_/get accessors round-trip it, and the kernel's accessor (the
// code both backends run) reads what the host wrote.
#include <gtest/gtest.h>

#include <cmath>

#include "kernel/kernel.hpp"

namespace {

using namespace vkrt::kernel;

// A distinct value for the n-th lane, of each type a param may have.
template <class T>
T distinct(uint n);
template <>
uint distinct<uint>(uint n) { return 1000u + n; }
template <>
float distinct<float>(uint n) { return 0.5f + float(n); }
template <>
vec3 distinct<vec3>(uint n) { return vec3(float(n), float(n) + 0.25f, float(n) + 0.5f); }
template <>
uvec3 distinct<uvec3>(uint n) { return uvec3(n, n + 1u, n + 2u); }

// Every value set to a distinct value, in table order.
Params every_value_set() {
    Params p{};
    uint n = 0;
#define PARAM(T, name, texel, lane) set_##name(p, distinct<T>(n++));
#define PARAM3(T, name, texel) set_##name(p, distinct<T>(n++));
#include "kernel/params.glsl"
    return p;
}

TEST(KernelParams, EachValueReadsBackWhatWasSetWhateverWasSetAfter) {
    const Params p = every_value_set();
    uint n = 0;
#define PARAM(T, name, texel, lane) EXPECT_EQ(name(p), distinct<T>(n++)) << #name;
#define PARAM3(T, name, texel) EXPECT_EQ(name(p), distinct<T>(n++)) << #name;
#include "kernel/params.glsl"
}

TEST(KernelParams, TheKernelReadsWhatTheHostWrote) {
    Kernel k;
    k.params = every_value_set();
#define PARAM(T, name, texel, lane) EXPECT_EQ(k.name(), name(k.params)) << #name;
#define PARAM3(T, name, texel) EXPECT_EQ(k.name(), name(k.params)) << #name;
#include "kernel/params.glsl"
}

// A vec3 leaves its texel's w lane zero, and a float is stored as its bits.
TEST(KernelParams, LanesHoldTheValuesBits) {
    Params p{};
    set_camera_eye(p, vec3(1.0f, -2.0f, 0.5f));
    EXPECT_EQ(p.texels[0], uvec4(0x3f800000u, 0xc0000000u, 0x3f000000u, 0u));
    set_min_ray_weight(p, -0.0f);
    EXPECT_EQ(std::signbit(min_ray_weight(p)), true);
    set_max_depth(p, 7u);
    EXPECT_EQ(max_depth(p), 7u);
}

}  // namespace
