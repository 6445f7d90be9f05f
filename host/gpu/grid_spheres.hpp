#pragma once
// The Vulkan backend's copy of each grid sphere beside its reference: render.comp's
// sphere tests in the grid read a sphere there (load_grid_sphere), at the reference's
// own position, rather than through the reference. On lavapipe that read no longer
// waits for the reference's, and a cell's spheres lie in consecutive texels instead
// of scattered over the sphere array (docs/grid.md, "Spheres beside their
// references"). The reference backend reads through the reference, which is faster
// there, so SceneGpu does not hold the copies: the Vulkan backend derives them when
// it uploads the scene.
#include <vector>

#include "scene/scene_gpu.hpp"

namespace vkrt::gpu {

// One center_radius per entry of scene.grid_refs: the sphere's for a sphere reference,
// zero for the other kinds. Empty when the grid lists no spheres, loose or in cells.
std::vector<glm::vec4> grid_sphere_copies(const SceneGpu& scene);

}  // namespace vkrt::gpu
