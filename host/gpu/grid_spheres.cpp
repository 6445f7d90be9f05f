#include "gpu/grid_spheres.hpp"

namespace vkrt::gpu {

std::vector<glm::vec4> grid_sphere_copies(const SceneGpu& scene) {
    if (!scene.features.has(Feature::GRID_SPHERES) && !scene.features.has(Feature::LOOSE_SPHERES)) {
        return {};
    }
    std::vector<glm::vec4> copies(scene.grid_refs.size(), glm::vec4(0.0f));
    for (std::size_t i = 0; i < scene.grid_refs.size(); ++i) {
        const std::uint32_t ref = scene.grid_refs[i];
        if ((ref >> kernel::REF_KIND_SHIFT) == kernel::REF_SPHERE) {
            copies[i] = scene.spheres.at(ref & kernel::REF_INDEX_MASK).center_radius;
        }
    }
    return copies;
}

}  // namespace vkrt::gpu
