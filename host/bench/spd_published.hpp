#pragma once
// Eric Haines' published ray counts for the Standard Procedural Databases at their
// default sizes, under the SPD test rules (513 x 513 eye rays through the pixel
// corners, ray-tree depth 5), as scenes/spd/README.md gives them. lattice,
// shells and jacks have no published row.
#include <array>
#include <cstdint>
#include <string_view>

namespace vkrt::bench {

struct SpdCounts {
    std::uint64_t eye_hits = 0;    // eye rays that hit something
    std::uint64_t reflection = 0;  // reflection rays
    std::uint64_t refraction = 0;  // refraction rays
    std::uint64_t shadow = 0;      // shadow rays
};

struct SpdPublished {
    std::string_view scene;  // the file's stem: "balls" for balls.nff
    SpdCounts counts;
};

inline constexpr std::array<SpdPublished, 7> kSpdPublished = {{
    {"balls", {263169, 175095, 0, 954368}},
    {"gears", {245086, 304643, 207564, 2246955}},
    {"mount", {173125, 354769, 354769, 412922}},
    {"rings", {263169, 315236, 0, 1085002}},
    {"teapot", {161120, 225248, 0, 407656}},
    {"tetra", {49788, 0, 0, 46112}},
    {"tree", {169836, 0, 0, 1097419}},
}};

// The published row for a scene, or none.
inline const SpdPublished* find_spd_published(std::string_view scene) {
    for (const SpdPublished& p : kSpdPublished) {
        if (p.scene == scene) return &p;
    }
    return nullptr;
}

}  // namespace vkrt::bench
