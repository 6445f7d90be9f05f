#include "render/fingerprint.hpp"

#include <fmt/format.h>

#include <vector>

namespace vkrt {
namespace {

// The features that say how the scene is traced, not what it shows.
bool is_acceleration_feature(std::uint32_t id) {
    switch (Feature(id)) {
    case Feature::DEFERRED_SPHERES:
    case Feature::HAS_GRID:
    case Feature::GRID_SPLIT: return true;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    case Feature::GRID_##NAMES:                                   \
    case Feature::LOOSE_##NAMES: return true;
#include "kernel/shapes/kinds.glsl"
    default: return false;
    }
}

}  // namespace

std::uint64_t scene_fingerprint(const FlatScene& scene) {
    kernel::Params params = scene.params;
    // The grid's box, cells, resolution and lookahead (see the header for why).
    for (auto* set : {kernel::set_grid_min, kernel::set_grid_max, kernel::set_grid_cell, kernel::set_grid_inv_cell}) {
        set(params, kernel::vec3(0.0f));
    }
    kernel::set_grid_resolution(params, kernel::uvec3(0u));
    Fnv1a h;
    h.add(&params, sizeof params);  // texels only: no padding bytes
    for (std::uint32_t id = 0; id < kFeatureCount; ++id) {
        const std::uint8_t on = !is_acceleration_feature(id) && scene.features.has(id) ? 1 : 0;
        h.add(&on, 1);
    }
    const std::uint8_t corners = scene.corners ? 1 : 0;
    h.add(&corners, 1);
    h.add(scene.materials);
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) h.add(scene.names);
#include "kernel/shapes/kinds.glsl"
    h.add(scene.lights);
    h.add(scene.emitters);
    return h.value();
}

std::string format_fingerprint(std::uint64_t fingerprint) { return fmt::format("{:016x}", fingerprint); }

}  // namespace vkrt
