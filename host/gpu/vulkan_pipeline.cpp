#include "gpu/vulkan_pipeline.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "gpu/spirv_specialize.hpp"
#include "gpu/vulkan_buffer.hpp"
#include "render_comp_spv.h"

namespace vkrt::gpu {

namespace {

constexpr VkFormat kFormat_rgba32ui = VK_FORMAT_R32G32B32A32_UINT;
constexpr VkFormat kFormat_r32ui = VK_FORMAT_R32_UINT;

// Dense numbering: binding i is the i-th line of the table.
constexpr bool bindings_dense() {
    std::uint32_t expected = 0;
    bool dense = true;
#define PARAMS_BUFFER(binding, name) dense = dense && binding == expected++;
#define SCENE_BUFFER(binding, name, Element, load, format) dense = dense && binding == expected++;
#define OUTPUT_BUFFER(binding, name, Element, format) dense = dense && binding == expected++;
#include "kernel/bindings.glsl"
    return dense;
}
static_assert(bindings_dense(), "kernel/bindings.glsl: bindings must be numbered 0, 1, 2, ... in order");

}  // namespace

VkFormat texel_format(std::uint32_t binding) {
    switch (binding) {
#define PARAMS_BUFFER(binding, name) \
    case binding: return kFormat_rgba32ui;
#define SCENE_BUFFER(binding, name, Element, load, format) \
    case binding: return kFormat_##format;
#define OUTPUT_BUFFER(binding, name, Element, format) \
    case binding: return kFormat_##format;
#include "kernel/bindings.glsl"
    default: return VK_FORMAT_UNDEFINED;
    }
}

std::uint32_t texel_bytes(std::uint32_t binding) {
    return texel_format(binding) == VK_FORMAT_R32_UINT ? 4u : 16u;
}

Pipeline make_compute_pipeline(VkDevice device, std::span<const std::uint32_t> spirv,
                               std::span<const VkDescriptorType> types, std::uint32_t push_bytes,
                               const VkSpecializationInfo* specialization) {
    Pipeline p;
    std::vector<VkDescriptorSetLayoutBinding> bindings(types.size());
    std::vector<VkDescriptorPoolSize> sizes;
    for (std::uint32_t i = 0; i < types.size(); ++i) {
        bindings[i] = {i, types[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        auto same = std::find_if(sizes.begin(), sizes.end(), [&](const VkDescriptorPoolSize& size) {
            return size.type == types[i];
        });
        if (same != sizes.end()) {
            ++same->descriptorCount;
        } else {
            sizes.push_back({types[i], 1});
        }
    }
    VkDescriptorSetLayoutCreateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_info.bindingCount = std::uint32_t(bindings.size());
    set_info.pBindings = bindings.data();
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout), "vkCreateDescriptorSetLayout");
    p.set_layout = {device, set_layout};

    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    layout_info.pushConstantRangeCount = push_bytes != 0 ? 1 : 0;
    layout_info.pPushConstantRanges = push_bytes != 0 ? &push : nullptr;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout), "vkCreatePipelineLayout");
    p.layout = {device, layout};

    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = spirv.size_bytes();
    module_info.pCode = spirv.data();
    VkShaderModule raw_module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(device, &module_info, nullptr, &raw_module), "vkCreateShaderModule");
    const DeviceHandle<VkShaderModule, vkDestroyShaderModule> module(device, raw_module);

    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = raw_module;
    pipeline_info.stage.pName = "main";
    pipeline_info.stage.pSpecializationInfo = specialization;
    pipeline_info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline),
          "vkCreateComputePipelines");
    p.pipeline = {device, pipeline};

    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = std::uint32_t(sizes.size());
    pool_info.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
    p.pool = {device, pool};

    VkDescriptorSetAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout;
    check(vkAllocateDescriptorSets(device, &alloc, &p.set), "vkAllocateDescriptorSets");
    return p;
}

Pipeline make_pipeline(const VulkanContext& context, const FeatureSet& features) {
    std::array<VkDescriptorType, kBindingCount> types{};
    types.fill(VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER);

    // One VkBool32 per feature, constant_id = feature id: a feature that is off is
    // compiled out by the driver.
    std::array<VkBool32, kFeatureCount> values{};
    std::array<VkSpecializationMapEntry, kFeatureCount> entries{};
    for (std::uint32_t id = 0; id < kFeatureCount; ++id) {
        values[id] = features.has(id) ? VK_TRUE : VK_FALSE;
        entries[id] = {id, std::uint32_t(id * sizeof(VkBool32)), sizeof(VkBool32)};
    }
    VkSpecializationInfo specialization{};
    specialization.mapEntryCount = kFeatureCount;
    specialization.pMapEntries = entries.data();
    specialization.dataSize = sizeof(values);
    specialization.pData = values.data();

    // The same values folded in on the host (spirv_specialize.hpp says why); should
    // SPIRV-Tools refuse, the driver specializes the module as it is.
    std::unordered_map<std::uint32_t, bool> by_id;
    for (std::uint32_t id = 0; id < kFeatureCount; ++id) by_id.emplace(id, values[id] == VK_TRUE);
    std::string error;
    const std::vector<std::uint32_t> specialized = specialize_spirv(render_comp_spv, by_id, error);
    if (specialized.empty()) {
        static bool warned = false;   // once a run: every pipeline would say the same
        if (!warned) {
            std::fprintf(stderr, "warning: SPIRV-Tools could not specialize the shader (%s); the driver will, and "
                                 "creating the pipeline takes longer\n", error.c_str());
            warned = true;
        }
    }
    const std::span<const std::uint32_t> words =
        specialized.empty() ? std::span<const std::uint32_t>(render_comp_spv)
                            : std::span<const std::uint32_t>(specialized);
    return make_compute_pipeline(context.device(), words, types, kPushBytes, &specialization);
}

std::vector<BufferView> write_descriptors(VkDevice device, VkDescriptorSet set,
                                          const std::array<const VulkanBuffer*, kBindingCount>& buffers) {
    std::vector<BufferView> views;
    std::array<VkBufferView, kBindingCount> raw_views{};
    std::array<VkWriteDescriptorSet, kBindingCount> writes{};
    for (std::uint32_t i = 0; i < kBindingCount; ++i) {
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
        VkBufferViewCreateInfo view_info{};
        view_info.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO;
        view_info.buffer = buffers[i]->get();
        view_info.format = texel_format(i);
        view_info.range = VK_WHOLE_SIZE;
        check(vkCreateBufferView(device, &view_info, nullptr, &raw_views[i]), "vkCreateBufferView");
        views.emplace_back(device, raw_views[i]);
        writes[i].pTexelBufferView = &raw_views[i];
    }
    vkUpdateDescriptorSets(device, kBindingCount, writes.data(), 0, nullptr);
    return views;
}

}  // namespace vkrt::gpu
