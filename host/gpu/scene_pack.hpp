#pragma once
// The Vulkan backend's one scene buffer: every array of kernel/arrays.glsl, one after
// another, so that the whole scene takes one binding however many arrays it has (the
// specification guarantees 4 storage texel buffers per stage). The rgba32ui arrays
// come first, counted in 16-byte texels from 0; the r32ui arrays follow from
// `words_start`, a texel aligned for a texel-buffer view of its own, counted in
// words from there. Where each array starts goes into the params (`<name>_base`,
// kernel/params.glsl). No Vulkan here, so the tests can check the layout.
#include <cstdint>
#include <vector>

#include "flatten/flat_scene.hpp"

namespace vkrt::gpu {

struct ScenePack {
    std::vector<kernel::uvec4> texels;  // the whole buffer, at least one texel
    std::uint32_t words_start = 0;      // texel where the r32ui arrays begin
    std::uint32_t word_count = 0;       // words of the r32ui arrays
    kernel::Params params{};            // the scene's, with every array's base set

    std::uint64_t bytes() const { return texels.size() * sizeof(kernel::uvec4); }
};

// `word_alignment` is the texel count words_start is a multiple of (a view's offset
// must be a multiple of minTexelBufferOffsetAlignment, at most 256 bytes).
ScenePack pack_scene(const FlatScene& scene, std::uint32_t word_alignment = 16);

}  // namespace vkrt::gpu
