#pragma once
// The environment around a scene: an equirectangular image of the radiance
// arriving from infinitely far away, in place of the one-colour background
// (kernel/environment.glsl says how directions map to texels, and how it is sampled).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/texture_image.hpp"

namespace vkrt {

struct Environment {
    LinearImage image;                    // linear rgb, rows from the top (toward `up`)
    double intensity = 1.0;               // multiplies the image's values
    double rotation = 0.0;                // degrees, right-handed about `up`
    glm::dvec3 up{0.0, 1.0, 0.0};         // unit: where the image's top row looks
};

// Larger images are halved until they fit: a few million texels resolve a sun
// and cost a device buffer of 16 bytes each.
inline constexpr std::uint64_t kMaxEnvironmentTexels = std::uint64_t(1) << 23;

// The image `file` as an environment (float formats linear, 8- and 16-bit ones
// sRGB-decoded). Negative values become 0 and a larger image than
// kMaxEnvironmentTexels is halved, each with a line in `warnings`. Throws
// SceneError naming `element` for a file that cannot be read or has a texel that
// is not finite.
Environment load_environment(const std::filesystem::path& file, const std::string& element,
                             std::vector<std::string>& warnings);

// The image halved in each direction, each texel the mean of the two by two it
// replaces (an odd last row or column is averaged with fewer).
LinearImage halve(const LinearImage& image);

}  // namespace vkrt
