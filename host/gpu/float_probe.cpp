#include "gpu/float_probe.hpp"

#include <array>

#include "float_probe_comp_spv.h"
#include "gpu/vulkan_buffer.hpp"
#include "gpu/vulkan_context.hpp"
#include "gpu/vulkan_pipeline.hpp"
#include "gpu/vulkan_devices.hpp"
#include "probe/float_cases.hpp"

namespace vkrt {

namespace {


constexpr std::uint32_t kProbeLocalSize = 64;  // local_size_x of float_probe.comp

// Binding 0: the cases, binding 1: the results; both storage buffers.
gpu::Pipeline make_probe_pipeline(VkDevice device, VkBuffer cases, VkBuffer results) {
    const std::array<VkDescriptorType, 2> types{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    gpu::Pipeline p = gpu::make_compute_pipeline(device, float_probe_comp_spv, types, 0, nullptr);
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
    const gpu::Pipeline p = make_probe_pipeline(context.device(), case_buffer.get(), result_buffer.get());

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
