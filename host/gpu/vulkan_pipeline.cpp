#include "gpu/vulkan_pipeline.hpp"

#include <algorithm>
#include <cstdio>
#include <unordered_map>
#include <utility>
#include <vector>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "gpu/pipeline_cache.hpp"
#include "gpu/spirv_specialize.hpp"
#include "gpu/vulkan_buffer.hpp"
#include "render_comp_address_spv.h"
#include "render_comp_spv.h"

namespace vkrt::gpu {

namespace {

constexpr VkFormat kFormat_rgba32ui = VK_FORMAT_R32G32B32A32_UINT;
constexpr VkFormat kFormat_r32ui = VK_FORMAT_R32_UINT;

// Dense numbering: binding i is the i-th line of the table.
constexpr bool bindings_dense() {
    std::uint32_t expected = 0;
    bool dense = true;
#define TEXEL_BINDING(binding, name, format, access) dense = dense && binding == expected++;
#define STORAGE_BINDING(binding, name, access) dense = dense && binding == expected++;
#define UNIFORM_BINDING(binding, name) dense = dense && binding == expected++;
#include "render_bindings.glsl"
    return dense;
}
static_assert(bindings_dense(), "render_bindings.glsl: bindings must be numbered 0, 1, 2, ... in order");

// The device choices' constant ids lie above the features'.
constexpr bool choices_after_features() {
    bool after = true;
#define DEVICE_CHOICE(id, name) after = after && id >= kFeatureCount;
#include "render_bindings.glsl"
    return after;
}
static_assert(choices_after_features(), "render_bindings.glsl: a device choice shares a feature's constant id");

}  // namespace

VkDescriptorType descriptor_type(Binding binding) {
    switch (binding) {
#define TEXEL_BINDING(binding, name, format, access) \
    case Binding::name: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
#define STORAGE_BINDING(binding, name, access) \
    case Binding::name: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
#define UNIFORM_BINDING(binding, name) \
    case Binding::name: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
#include "render_bindings.glsl"
    }
    return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

VkFormat texel_format(Binding binding) {
    switch (binding) {
#define TEXEL_BINDING(binding, name, format, access) \
    case Binding::name: return kFormat_##format;
#include "render_bindings.glsl"
    default: return VK_FORMAT_UNDEFINED;
    }
}

Pipeline make_compute_pipeline(VkDevice device, std::span<const std::uint32_t> spirv,
                               std::span<const VkDescriptorType> types, std::uint32_t push_bytes,
                               const VkSpecializationInfo* specialization, VkPipelineCache cache) {
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
    check(vkCreateComputePipelines(device, cache, 1, &pipeline_info, nullptr, &pipeline),
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

Pipeline make_pipeline(const VulkanContext& context, const FeatureSet& features, const DataPaths& paths) {
    std::array<VkDescriptorType, kBindingCount> types{};
    for (std::uint32_t i = 0; i < kBindingCount; ++i) types[i] = descriptor_type(Binding(i));

    // One VkBool32 per constant: a feature that is off, and a data path the device
    // does not take, are compiled out by the driver.
    std::vector<std::pair<std::uint32_t, bool>> constants;
    for (std::uint32_t id = 0; id < kFeatureCount; ++id) constants.emplace_back(id, features.has(id));
    const bool SCENE_IN_STORAGE_BUFFERS = paths.scene_in_storage;
    const bool PARAMS_IN_UNIFORM_BUFFER = paths.params_in_uniform;
#define DEVICE_CHOICE(id, name) constants.emplace_back(id, name);
#include "render_bindings.glsl"
    std::vector<VkBool32> values;
    std::vector<VkSpecializationMapEntry> entries;
    std::unordered_map<std::uint32_t, bool> by_id;
    for (const auto& [id, on] : constants) {
        entries.push_back({id, std::uint32_t(values.size() * sizeof(VkBool32)), sizeof(VkBool32)});
        values.push_back(on ? VK_TRUE : VK_FALSE);
        by_id.emplace(id, on);
    }
    VkSpecializationInfo specialization{};
    specialization.mapEntryCount = std::uint32_t(entries.size());
    specialization.pMapEntries = entries.data();
    specialization.dataSize = values.size() * sizeof(VkBool32);
    specialization.pData = values.data();

    // The same values folded in on the host (spirv_specialize.hpp says why); should
    // SPIRV-Tools refuse, the driver specializes the module as it is.
    const std::span<const std::uint32_t> module =
        paths.scene_by_address ? std::span<const std::uint32_t>(render_comp_address_spv)
                               : std::span<const std::uint32_t>(render_comp_spv);
    // A feature set specialized before is read back rather than specialized again
    // (gpu/pipeline_cache.hpp).
    const std::uint64_t key = specialization_key(module, by_id);
    std::vector<std::uint32_t> specialized = read_cached_spirv(context.cache_dir(), key);
    std::string error;
    if (specialized.empty()) {
        specialized = specialize_spirv(module, by_id, error);
        if (!specialized.empty()) write_cached_spirv(context.cache_dir(), key, specialized);
    }
    if (specialized.empty()) {
        static bool warned = false;   // once a run: every pipeline would say the same
        if (!warned) {
            std::fprintf(stderr, "warning: SPIRV-Tools could not specialize the shader (%s); the driver will, and "
                                 "creating the pipeline takes longer\n", error.c_str());
            warned = true;
        }
    }
    const std::span<const std::uint32_t> words =
        specialized.empty() ? module : std::span<const std::uint32_t>(specialized);
    Pipeline pipeline =
        make_compute_pipeline(context.device(), words, types, kPushBytes, &specialization, context.pipeline_cache());
    context.save_pipeline_cache();
#ifdef __GLIBC__
    // The driver's compiler has freed its working memory (lavapipe's NIR of the
    // kernel, tens of MiB, in small blocks that the C library keeps): hand the free
    // heap back, so that the scene's buffers made next do not stack on it in peak
    // memory (35 MB of the helmet-sized asset's, decision 0037).
    malloc_trim(0);
#endif
    return pipeline;
}

std::vector<BufferView> write_descriptors(VkDevice device, VkDescriptorSet set,
                                          const std::array<BoundRange, kBindingCount>& bound) {
    std::vector<BufferView> views;
    std::array<VkBufferView, kBindingCount> raw_views{};
    std::array<VkDescriptorBufferInfo, kBindingCount> infos{};
    std::array<VkWriteDescriptorSet, kBindingCount> writes{};
    for (std::uint32_t i = 0; i < kBindingCount; ++i) {
        const VkDescriptorType type = descriptor_type(Binding(i));
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = type;
        if (type != VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER) {
            infos[i] = {bound[i].buffer->get(), bound[i].offset, bound[i].range};
            writes[i].pBufferInfo = &infos[i];
            continue;
        }
        VkBufferViewCreateInfo view_info{};
        view_info.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO;
        view_info.buffer = bound[i].buffer->get();
        view_info.format = texel_format(Binding(i));
        view_info.offset = bound[i].offset;
        view_info.range = bound[i].range;
        check(vkCreateBufferView(device, &view_info, nullptr, &raw_views[i]), "vkCreateBufferView");
        views.emplace_back(device, raw_views[i]);
        writes[i].pTexelBufferView = &raw_views[i];
    }
    vkUpdateDescriptorSets(device, kBindingCount, writes.data(), 0, nullptr);
    return views;
}

}  // namespace vkrt::gpu
