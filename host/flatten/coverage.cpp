#include "flatten/coverage.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <map>
#include <span>

#include <glm/gtc/packing.hpp>

namespace vkrt {

bool fully_opaque(const Scene& scene, const TextureImage& t) {
    const std::span<const std::uint32_t> words = scene.texels.words().subspan(t.first_word, t.word_count());
    if (t.format == TexelFormat::Rgba8) {
        return std::all_of(words.begin(), words.end(), [](std::uint32_t w) { return (w >> 24u) == 255u; });
    }
    // Half: (red, green), (blue, alpha), alpha the high half of the second word.
    for (std::size_t i = 1; i < words.size(); i += 2) {
        if (glm::unpackHalf1x16(std::uint16_t(words[i] >> 16u)) < 1.0f) return false;
    }
    return true;
}

std::vector<bool> coverage_tested(const Scene& scene) {
    std::vector<bool> tested(scene.materials.size(), false);
    // Materials of a triangle whose vertex colours have an alpha below 1.
    std::vector<bool> vertex_alpha(scene.materials.size(), false);
    for (const Triangle& t : scene.triangles) {
        if (!t.colors) continue;
        for (const glm::vec4& c : *t.colors) vertex_alpha[t.material] = vertex_alpha[t.material] || c.a < 1.0f;
    }
    std::map<std::uint32_t, bool> opaque_texture;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        if (m.alpha_mode == AlphaMode::Opaque) continue;
        bool constant = !vertex_alpha[i];  // the opacity is m.alpha everywhere
        if (m.texture) {
            auto [at, fresh] = opaque_texture.try_emplace(*m.texture, false);
            if (fresh) at->second = fully_opaque(scene, scene.textures[*m.texture]);
            constant = at->second;
        }
        const bool opaque = m.alpha_mode == AlphaMode::Mask ? m.alpha >= m.alpha_cutoff : m.alpha >= 1.0;
        tested[i] = !(constant && opaque);
    }
    return tested;
}

}  // namespace vkrt
