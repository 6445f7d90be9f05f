#pragma once
// The compute pipeline of shaders/render.comp, specialised for a scene's feature set,
// and its one descriptor set.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/vulkan_context.hpp"
#include "flatten/features.hpp"

namespace vkrt::gpu {

class VulkanBuffer;

// The bindings of shaders/render.comp, one per line of kernel/bindings.glsl, named as
// there. A binding whose feature the scene leaves out gets the dummy buffer.
enum class Binding : std::uint32_t {
#define PARAMS_BUFFER(binding, name) name = binding,
#define SCENE_BUFFER(binding, name, Element, load, format) name = binding,
#define OUTPUT_BUFFER(binding, name, Element, format) name = binding,
#include "kernel/bindings.glsl"
};
constexpr std::uint32_t kBindingCount = 0
#define PARAMS_BUFFER(binding, name) +1
#define SCENE_BUFFER(binding, name, Element, load, format) +1
#define OUTPUT_BUFFER(binding, name, Element, format) +1
#include "kernel/bindings.glsl"
    ;
constexpr std::uint32_t index(Binding b) { return static_cast<std::uint32_t>(b); }
// Each binding's texel format, by binding number, and the bytes of one texel.
VkFormat texel_format(std::uint32_t binding);
std::uint32_t texel_bytes(std::uint32_t binding);

constexpr std::uint32_t kLocalSize = 8;   // local_size_x and _y of render.comp
constexpr std::uint32_t kPushBytes = 16;  // uvec4 pass

// Every binding is a storage texel buffer of 16-byte texels (r32ui for the grid's cell
// starts and references; render.comp says why): the params, the read-only scene arrays
// and the sums.
constexpr VkBufferUsageFlags kBindingUsage = VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT;

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
// and one descriptor set from a pool sized for exactly those bindings. Shared by the
// renderer and the float probe (gpu/float_probe.cpp).
Pipeline make_compute_pipeline(VkDevice device, std::span<const std::uint32_t> spirv,
                               std::span<const VkDescriptorType> types, std::uint32_t push_bytes,
                               const VkSpecializationInfo* specialization);

// The renderer's pipeline (render.comp), specialized for the scene's features.
Pipeline make_pipeline(const VulkanContext& context, const FeatureSet& features);

using BufferView = DeviceHandle<VkBufferView, vkDestroyBufferView>;

// Writes the set, one buffer per binding; returns the texel-buffer views, which must
// outlive its use.
std::vector<BufferView> write_descriptors(VkDevice device, VkDescriptorSet set,
                                          const std::array<const VulkanBuffer*, kBindingCount>& buffers);

}  // namespace vkrt::gpu
