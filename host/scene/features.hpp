#pragma once
// The feature set a scene needs (DESIGN.md principle 3). The list of features is
// shaders/kernel/features.glsl, shared with the kernel, where each becomes a
// specialization constant (Vulkan) or a Kernel member (reference).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace vkrt {

enum class Feature : std::uint32_t {
#define FEATURE(id, name) name = id,
#include "kernel/features.glsl"
#undef FEATURE
};

// One past the largest feature id. Ids need not be dense (while branches that add
// features are apart, an id may be reserved for a feature this build does not have),
// so every per-id table has kFeatureCount slots and feature_exists() says which are
// real.
inline constexpr std::uint32_t kFeatureCount = std::max({0u
#define FEATURE(id, name) , std::uint32_t(id) + 1u
#include "kernel/features.glsl"
#undef FEATURE
});

// Whether `id` names a feature of this build (not a gap in the ids).
bool feature_exists(std::uint32_t id);

class FeatureSet {
public:
    bool has(Feature f) const { return on_[static_cast<std::uint32_t>(f)]; }
    void set(Feature f, bool value) { on_[static_cast<std::uint32_t>(f)] = value; }
    bool has(std::uint32_t id) const { return on_[id]; }

    // Lower-case names without the HAS_ prefix, e.g. "smooth_normals"; gaps in the
    // ids are in neither list.
    std::vector<std::string> kept() const;
    std::vector<std::string> left_out() const;

private:
    std::array<bool, kFeatureCount> on_{};
};

// The name of a feature as the logs and stats show it.
std::string feature_name(std::uint32_t id);

// What the scene needs, nothing more.
FeatureSet analyze_features(const Scene& scene);

}  // namespace vkrt
