#pragma once
// The feature set a scene needs (docs/architecture.md, principle 3). The list of features is
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

inline constexpr std::uint32_t kFeatureCount = 0
#define FEATURE(id, name) +1
#include "kernel/features.glsl"
#undef FEATURE
    ;

// The ids index arrays (and are specialization constant ids): they must run 0, 1,
// 2, ... without gaps. With distinct ids, each below the count means exactly that.
#define FEATURE(id, name) static_assert((id) < kFeatureCount, #name ": feature ids must be dense");
#include "kernel/features.glsl"
#undef FEATURE

class FeatureSet {
public:
    bool has(Feature f) const { return on_[static_cast<std::uint32_t>(f)]; }
    void set(Feature f, bool value) { on_[static_cast<std::uint32_t>(f)] = value; }
    bool has(std::uint32_t id) const { return on_[id]; }

    // Lower-case names without the HAS_ prefix, e.g. "smooth_normals".
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
