#pragma once
// The reference backend's view of the kernel: the GLSL files of shaders/kernel/ are
// included inside a struct whose members carry the same names as the shader's
// uniforms, specialization constants and buffer accessors (load_sphere, ...), so the
// very same text compiles as C++ member functions (docs/architecture.md, "The shared kernel,
// concretely"; docs/architecture.md says why buffers are read through accessors).
// One Kernel object plays the part of one invocation's private state: make one per
// thread.
#include <span>

#include "kernel_types.hpp"

namespace vkrt::kernel {

#define INOUT(T) T&
#define precise

struct Kernel {
#define FEATURE(id, name) bool name = true;
#include "kernel/features.glsl"
#undef FEATURE

    Params params{};
    std::span<const Material> materials;
    std::span<const Sphere> spheres;
    std::span<const Triangle> triangles;
    std::span<const PointLight> lights;
    std::span<const Emitter> emitters;
    std::span<const uint> grid_cell_starts;
    std::span<const uint> grid_refs;
    std::span<const Ring> rings;
    std::span<const Cylinder> cylinders;

    // The accessors the kernel reads the scene through (render.comp has the GLSL ones).
    Material load_material(uint i) const { return materials[i]; }
    Sphere load_sphere(uint i) const { return spheres[i]; }
    Triangle load_triangle(uint i) const { return triangles[i]; }
    PointLight load_light(uint i) const { return lights[i]; }
    Ring load_ring(uint i) const { return rings[i]; }
    Cylinder load_cylinder(uint i) const { return cylinders[i]; }
    Emitter load_emitter(uint i) const { return emitters[i]; }
    uint load_cell_start(uint i) const { return grid_cell_starts[i]; }
    uint load_ref(uint i) const { return grid_refs[i]; }
    // Reads the sphere array at `index`, not a copy at `position` beside the
    // references as the Vulkan backend does (gpu/grid_spheres.hpp): the copies made
    // the reference slower (docs/grid.md, "Spheres beside their references"). So only
    // Vulkan renders can catch a wrong `position`.
    vec4 load_grid_sphere(uint /*position*/, uint index) const { return spheres[index].center_radius; }

#include "kernel/all.glsl"
};

#undef precise
#undef INOUT

}  // namespace vkrt::kernel
