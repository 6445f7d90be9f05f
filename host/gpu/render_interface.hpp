#pragma once
// What the host must agree with shaders/render.comp on, beside its descriptor set
// (render_bindings.glsl): the workgroup's side and the push constants. Declared once
// here for every file of host/gpu/, Vulkan or not.
#include <cstdint>

namespace vkrt::gpu {

constexpr std::uint32_t kWorkgroupSide = 8;  // local_size_x and _y
// Push constants: uvec4 pass, uvec4 bases[4] (scene_pack.hpp's ScenePack::bases),
// then uvec4 scene_address (the scene buffer's device address in its first 8 bytes).
constexpr std::uint32_t kPassBytes = 16;
constexpr std::uint32_t kBaseLanes = 16;
constexpr std::uint32_t kBasesBytes = 4 * kBaseLanes;
constexpr std::uint32_t kAddressBytes = 16;
constexpr std::uint32_t kPushBytes = kPassBytes + kBasesBytes + kAddressBytes;

}  // namespace vkrt::gpu
