#pragma once
// The Vulkan backend's copy of each grid sphere beside its reference: render.comp's
// sphere tests in the grid read a sphere there (load_grid_sphere), at the reference's
// own position, rather than through the reference. On lavapipe that read no longer
// waits for the reference's, and a cell's spheres lie in consecutive texels instead
// of scattered over the sphere array (docs/grid.md, "Spheres beside their
// references"). The reference backend reads through the reference, which is faster
// there, so SceneGpu does not hold the copies: the Vulkan backend writes them
// straight into their buffer when it uploads the scene, with no host array between
// (a million spheres have 7 million references: 112 MiB of copies).
#include <cstddef>

#include "scene/scene_gpu.hpp"

namespace vkrt::gpu {

// How many copies: one per entry of scene.grid_refs where the cells list spheres, one
// per loose reference (the first grid_cell_starts[0]) where only the loose ones hold
// spheres, none where neither does.
std::size_t grid_sphere_copy_count(const SceneGpu& scene);

// Writes grid_sphere_copy_count(scene) center_radius values to `out`: the sphere's for
// a sphere reference, zero for the other kinds.
void write_grid_sphere_copies(const SceneGpu& scene, glm::vec4* out);

}  // namespace vkrt::gpu
