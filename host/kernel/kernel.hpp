#pragma once
// The reference backend's view of the kernel: the GLSL files of shaders/kernel/ are
// included inside a struct whose members carry the same names as the shader's
// specialization constants, params and buffers, so the very same text, the buffer
// loaders (kernel/loads.glsl) among it, compiles as C++ member functions
// (docs/architecture.md, "The shared kernel").
// One Kernel object plays the part of one invocation's private state: make one per
// thread.
#include <span>

#include "kernel/checks.hpp"
#include "kernel/types.hpp"

namespace vkrt::kernel {

#define INOUT(T) T&
#define precise
#define CHECK(condition) VKRT_KERNEL_CHECK(condition)
// The grid walk's small functions, which GCC otherwise leaves as calls that keep
// the walk's state in memory.
#define HOT [[gnu::always_inline]] inline

struct Kernel {
#define FEATURE(id, name) bool name = true;
#include "kernel/features.glsl"
#undef FEATURE

    // What render.comp's main() reads from its params buffer.
    Params params{};
    // One span per array the kernel reads (kernel/arrays.glsl): those of FlatScene.
#define SCENE_ARRAY(id, name, Element, load, format) std::span<const Element> name;
#include "kernel/arrays.glsl"

#define LOAD_ELEMENT(Element, name, i) name[i]
#include "kernel/all.glsl"
#undef LOAD_ELEMENT
};

#undef HOT
#undef CHECK
#undef precise
#undef INOUT

}  // namespace vkrt::kernel
