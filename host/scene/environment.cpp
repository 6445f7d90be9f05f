#include "scene/environment.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace vkrt {

LinearImage halve(const LinearImage& image) {
    LinearImage out;
    out.name = image.name;
    out.width = std::max<std::uint32_t>(1, image.width / 2);
    out.height = std::max<std::uint32_t>(1, image.height / 2);
    out.texels.assign(std::size_t(out.width) * out.height, glm::vec4(0.0f));
    for (std::uint32_t y = 0; y < out.height; ++y) {
        for (std::uint32_t x = 0; x < out.width; ++x) {
            // The source texels this one covers: two by two, three at an odd edge.
            const std::uint32_t x1 = x + 1 == out.width ? image.width : 2 * x + 2;
            const std::uint32_t y1 = y + 1 == out.height ? image.height : 2 * y + 2;
            glm::dvec4 sum(0.0);
            for (std::uint32_t sy = 2 * y; sy < y1; ++sy) {
                for (std::uint32_t sx = 2 * x; sx < x1; ++sx) sum += glm::dvec4(image.texels[sy * image.width + sx]);
            }
            out.texels[std::size_t(y) * out.width + x] = glm::vec4(sum / double((x1 - 2 * x) * (y1 - 2 * y)));
        }
    }
    return out;
}

Environment load_environment(const std::filesystem::path& file, const std::string& element,
                             std::vector<std::string>& warnings) {
    Environment env;
    env.image = load_linear_image(file, Encoding::SrgbUnlessFloat, element);
    std::size_t negative = 0;
    for (glm::vec4& t : env.image.texels) {
        for (int c = 0; c < 3; ++c) {
            if (t[c] < 0.0f) {
                t[c] = 0.0f;
                ++negative;
            }
        }
    }
    if (negative != 0) {
        warnings.push_back(fmt::format("{}: environment {}: {} negative channel values read as 0", element,
                                       env.image.name, negative));
    }
    const std::uint32_t width = env.image.width, height = env.image.height;
    while (std::uint64_t(env.image.width) * env.image.height > kMaxEnvironmentTexels) env.image = halve(env.image);
    if (env.image.width != width) {
        warnings.push_back(fmt::format("{}: environment {}: {} x {} texels reduced to {} x {} (at most {} texels)", element,
                                       env.image.name, width, height, env.image.width, env.image.height,
                                       kMaxEnvironmentTexels));
    }
    return env;
}

}  // namespace vkrt
