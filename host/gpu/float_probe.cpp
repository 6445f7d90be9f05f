#include "gpu/float_probe.hpp"

#include <array>

#include "float_probe_comp_spv.h"
#include "gpu/vulkan_buffer.hpp"
#include "gpu/vulkan_context.hpp"
#include "gpu/vulkan_devices.hpp"
#include "probe/float_cases.hpp"

namespace vkrt {

namespace {

using gpu::check;
using gpu::DeviceHandle;

constexpr std::uint32_t kProbeLocalSize = 64;  // local_size_x of float_probe.comp

// Binding 0: the cases, binding 1: the results; both storage buffers.
struct ProbePipeline {
    DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> set_layout;
    DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout;
    DeviceHandle<VkPipeline, vkDestroyPipeline> pipeline;
    DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool;
    VkDescriptorSet set = VK_NULL_HANDLE;  // freed with the pool
};

ProbePipeline make_probe_pipeline(VkDevice device, VkBuffer cases, VkBuffer results) {
    ProbePipeline p;
    std::array<VkDescriptorSetLayoutBinding, 2> bindings{};
    for (std::uint32_t i = 0; i < 2; ++i) {
        bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    }
    VkDescriptorSetLayoutCreateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_info.bindingCount = 2;
    set_info.pBindings = bindings.data();
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout), "vkCreateDescriptorSetLayout");
    p.set_layout = {device, set_layout};

    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout), "vkCreatePipelineLayout");
    p.layout = {device, layout};

    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = sizeof(float_probe_comp_spv);
    module_info.pCode = float_probe_comp_spv;
    VkShaderModule raw_module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(device, &module_info, nullptr, &raw_module), "vkCreateShaderModule");
    const DeviceHandle<VkShaderModule, vkDestroyShaderModule> module(device, raw_module);

    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = raw_module;
    pipeline_info.stage.pName = "main";
    pipeline_info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline),
          "vkCreateComputePipelines");
    p.pipeline = {device, pipeline};

    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
    p.pool = {device, pool};

    VkDescriptorSetAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout;
    check(vkAllocateDescriptorSets(device, &alloc, &p.set), "vkAllocateDescriptorSets");

    const std::array<VkDescriptorBufferInfo, 2> infos{{{cases, 0, VK_WHOLE_SIZE}, {results, 0, VK_WHOLE_SIZE}}};
    std::array<VkWriteDescriptorSet, 2> writes{};
    for (std::uint32_t i = 0; i < 2; ++i) {
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = p.set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(device, 2, writes.data(), 0, nullptr);
    return p;
}

DeviceProbeRun probe_one(const VulkanOptions& options) {
    const gpu::VulkanContext context(options);
    const std::vector<probe::ProbeCase> cases = probe::probe_cases();
    const VkDeviceSize case_bytes = cases.size() * sizeof(probe::ProbeCase);
    const VkDeviceSize result_bytes = cases.size() * sizeof(glm::vec4);
    gpu::VulkanBuffer case_buffer(context, "float probe cases", case_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    gpu::VulkanBuffer result_buffer(context, "float probe results", result_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    case_buffer.upload(cases.data(), case_bytes);
    const ProbePipeline p = make_probe_pipeline(context.device(), case_buffer.get(), result_buffer.get());

    const auto groups = static_cast<std::uint32_t>((cases.size() + kProbeLocalSize - 1) / kProbeLocalSize);
    context.submit_and_wait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline.get());
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout.get(), 0, 1, &p.set, 0, nullptr);
        vkCmdDispatch(cmd, groups, 1, 1);
    });
    DeviceProbeRun run;
    run.device = context.properties().deviceName;
    run.results.resize(cases.size());
    result_buffer.readback(run.results.data(), result_bytes);
    if (options.validation && context.validation_messages() > 0) {
        throw GpuError("the float probe on " + run.device + " raised " +
                       std::to_string(context.validation_messages()) + " validation messages");
    }
    return run;
}

}  // namespace

std::vector<DeviceProbeRun> run_vulkan_float_probe(const VulkanOptions& options) {
    if (!options.device.empty()) {
        return {probe_one(options)};
    }
    std::vector<DeviceProbeRun> runs;
    std::vector<gpu::PhysicalDevice> devices;
    {
        const gpu::VulkanInstance instance(false);
        devices = instance.devices();
    }
    for (const gpu::PhysicalDevice& d : devices) {
        // select_device refuses, with the reason, a device that cannot run vkrt; the
        // profile is about the devices vkrt can render on, so those are skipped here.
        if (!d.has_compute || d.api_version < VK_API_VERSION_1_1) {
            continue;
        }
        VulkanOptions one = options;
        one.device = std::to_string(d.info.index);
        runs.push_back(probe_one(one));
    }
    if (runs.empty()) {
        throw GpuError(std::string("no Vulkan device can run the float probe: ") + gpu::kNoDriverHint);
    }
    return runs;
}

}  // namespace vkrt
