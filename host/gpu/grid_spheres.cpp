#include "gpu/grid_spheres.hpp"

namespace vkrt::gpu {

std::size_t grid_sphere_copy_count(const SceneGpu& scene) {
    if (scene.features.has(Feature::GRID_SPHERES)) {
        return scene.grid_refs.size();
    }
    // Only the loose references, which come first, can be spheres.
    return scene.features.has(Feature::LOOSE_SPHERES) ? scene.grid_cell_starts.front() : 0;
}

void write_grid_sphere_copies(const SceneGpu& scene, glm::vec4* out) {
    const std::size_t count = grid_sphere_copy_count(scene);
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t ref = scene.grid_refs[i];
        out[i] = (ref >> kernel::REF_KIND_SHIFT) == kernel::REF_SPHERE
                     ? scene.spheres.at(ref & kernel::REF_INDEX_MASK).center_radius
                     : glm::vec4(0.0f);
    }
}

}  // namespace vkrt::gpu
