#include "gpu/scene_pack.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "gpu/vulkan_backend.hpp"

namespace vkrt::gpu {

namespace {

constexpr bool kWords_rgba32ui = false;
constexpr bool kWords_r32ui = true;

// The kernel indexes the buffer with a signed 32-bit texel number.
constexpr std::uint64_t kMaxTexels = std::uint64_t(1) << 31;

// `count` texels or words.
void check_size(std::uint64_t count) {
    if (count >= kMaxTexels) {
        throw GpuError("scene: its arrays need more than one buffer of 2^31 texels (32 GiB) holds");
    }
}

template <typename Array>
std::uint64_t texels_of(const Array& items) {
    return (items.size() * sizeof(typename Array::value_type) + 15) / 16;
}

}  // namespace

ScenePack pack_scene(const FlatScene& scene, std::uint32_t word_alignment) {
    ScenePack pack;
    std::uint64_t texels = 0;
#define SCENE_ARRAY(id, name, Element, load, format)                                   \
    if (!kWords_##format) {                                                        \
        pack.bases[id] = std::uint32_t(texels);                  \
        texels += texels_of(scene.name);                                           \
        check_size(texels);                                                        \
    }
#include "kernel/arrays.glsl"
    std::uint64_t words = 0;
#define SCENE_ARRAY(id, name, Element, load, format) \
    if (kWords_##format) words += scene.name.size();
#include "kernel/arrays.glsl"
    // The imageLoad of a word takes a signed 32-bit index too.
    check_size(words);
    // Aligned for a view of its own, where there are words to view.
    const std::uint64_t align = word_alignment == 0 || words == 0 ? 1 : word_alignment;
    const std::uint64_t words_start = (texels + align - 1) / align * align;
    check_size(words_start + (words + 3) / 4);
    words = 0;
#define SCENE_ARRAY(id, name, Element, load, format)                                   \
    if (kWords_##format) {                                                         \
        pack.bases[id] = std::uint32_t(words);                    \
        words += scene.name.size();                                                \
    }
#include "kernel/arrays.glsl"
    pack.words_start = std::uint32_t(words_start);
    pack.word_count = std::uint32_t(words);
    pack.bases[kSceneArrays] = pack.words_start;

    pack.texel_count = std::max<std::uint64_t>(words_start + (words + 3) / 4, 1);
    return pack;
}

void write_scene(const FlatScene& scene, const ScenePack& pack, void* out) {
    auto* bytes = static_cast<unsigned char*>(out);
    std::memset(bytes, 0, pack.bytes());
#define SCENE_ARRAY(id, name, Element, load, format)                                                         \
    if (!scene.name.empty()) {                                                                           \
        const std::size_t at = kWords_##format ? std::size_t(pack.words_start) * 16 + std::size_t(pack.bases[id]) * 4 \
                                               : std::size_t(pack.bases[id]) * 16;                       \
        std::memcpy(bytes + at, scene.name.data(), scene.name.size() * sizeof(scene.name[0]));           \
    }
#include "kernel/arrays.glsl"
}

}  // namespace vkrt::gpu
