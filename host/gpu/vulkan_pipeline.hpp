#pragma once
// The compute pipeline of shaders/render.comp, specialised for a scene's feature set,
// and its one descriptor set.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/vulkan_context.hpp"
#include "flatten/features.hpp"
#include "gpu/data_paths.hpp"
#include "gpu/render_interface.hpp"

namespace vkrt::gpu {

class VulkanBuffer;

// The bindings of shaders/render.comp, one per line of render_bindings.glsl, named
// as there.
enum class Binding : std::uint32_t {
#define TEXEL_BINDING(binding, name, format, access) name = binding,
#define STORAGE_BINDING(binding, name, access) name = binding,
#define UNIFORM_BINDING(binding, name) name = binding,
#include "render_bindings.glsl"
};
constexpr std::uint32_t kBindingCount = 0
#define TEXEL_BINDING(binding, name, format, access) +1
#define STORAGE_BINDING(binding, name, access) +1
#define UNIFORM_BINDING(binding, name) +1
#include "render_bindings.glsl"
    ;
constexpr std::uint32_t index(Binding b) { return static_cast<std::uint32_t>(b); }
// Each binding's descriptor type, and for a texel buffer its format.
VkDescriptorType descriptor_type(Binding binding);
VkFormat texel_format(Binding binding);


// What a buffer bound to render.comp may be bound as; each binding uses one.
constexpr VkBufferUsageFlags kBindingUsage = VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT |
                                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                             VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;

// The pipeline and its descriptor set. Members are destroyed in reverse order.
struct Pipeline {
    DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> set_layout;
    DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout;
    DeviceHandle<VkPipeline, vkDestroyPipeline> pipeline;
    DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool;
    VkDescriptorSet set = VK_NULL_HANDLE;  // freed with the pool
};

// A compute pipeline from SPIR-V words: a set layout with one binding per entry of
// `types` (binding i of type types[i]), a pipeline layout with `push_bytes` of push
// constants (0: none), the pipeline (specialized when `specialization` is given),
// and one descriptor set from a pool sized for exactly those bindings, compiled
// through `cache` when one is given. Shared by the renderer and the float probe
// (gpu/float_probe.cpp).
Pipeline make_compute_pipeline(VkDevice device, std::span<const std::uint32_t> spirv,
                               std::span<const VkDescriptorType> types, std::uint32_t push_bytes,
                               const VkSpecializationInfo* specialization, VkPipelineCache cache = VK_NULL_HANDLE);

// The renderer's pipeline (render.comp), specialized for the scene's features and
// the device's data paths.
Pipeline make_pipeline(const VulkanContext& context, const FeatureSet& features, const DataPaths& paths);

using BufferView = DeviceHandle<VkBufferView, vkDestroyBufferView>;

// A part of a buffer bound to one binding.
struct BoundRange {
    const VulkanBuffer* buffer = nullptr;
    VkDeviceSize offset = 0;
    VkDeviceSize range = VK_WHOLE_SIZE;
};

// Writes the set, one range per binding; returns the texel-buffer views, which must
// outlive its use.
std::vector<BufferView> write_descriptors(VkDevice device, VkDescriptorSet set,
                                          const std::array<BoundRange, kBindingCount>& bound);

}  // namespace vkrt::gpu
