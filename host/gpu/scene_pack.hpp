#pragma once
// The Vulkan backend's one scene buffer: every array of kernel/arrays.glsl, one after
// another, so that the whole scene takes one binding however many arrays it has (the
// specification guarantees 4 storage texel buffers per stage). The rgba32ui arrays
// come first, counted in 16-byte texels from 0; the r32ui arrays follow from
// `words_start`, a texel aligned for a texel-buffer view of its own, counted in
// words from there. Where each array starts reaches render.comp in its push
// constants (`bases`). No Vulkan here, so the tests can check the layout.
#include <array>
#include <cstdint>
#include <vector>

#include "flatten/flat_scene.hpp"
#include "gpu/render_interface.hpp"

namespace vkrt::gpu {

// The arrays of kernel/arrays.glsl, and one more lane for words_start.
constexpr std::uint32_t kSceneArrays = 0
#define SCENE_ARRAY(id, name, Element, load, format) +1
#include "kernel/arrays.glsl"
    ;
static_assert(kSceneArrays + 1 <= kBaseLanes, "kernel/arrays.glsl: more arrays than render.comp's bases hold");

// Where each array goes in the buffer. The buffer is written by write_scene, straight
// into the device's memory where it is mapped: a scene's textures are not copied
// once more on their way.
struct ScenePack {
    std::uint64_t texel_count = 1;  // the whole buffer, at least one texel
    std::uint32_t words_start = 0;  // texel where the r32ui arrays begin
    std::uint32_t word_count = 0;   // words of the r32ui arrays
    // By array id: where it starts (texels, or words from words_start); lane
    // kSceneArrays holds words_start.
    std::array<std::uint32_t, kBaseLanes> bases{};

    std::uint64_t bytes() const { return texel_count * sizeof(kernel::uvec4); }
};

// `word_alignment` is the texel count words_start is a multiple of (a view's offset
// must be a multiple of minTexelBufferOffsetAlignment, at most 256 bytes).
ScenePack pack_scene(const FlatScene& scene, std::uint32_t word_alignment = 16);

// The buffer's bytes (pack.bytes() of them at `out`): each array where the pack says,
// zeros between.
void write_scene(const FlatScene& scene, const ScenePack& pack, void* out);

}  // namespace vkrt::gpu
