#include "gpu/device_limits.hpp"

#include <algorithm>
#include <array>

#include "gpu/render_interface.hpp"
#include "gpu/vulkan_backend.hpp"
#include "kernel/types.hpp"

namespace vkrt::gpu {

namespace {

// What render.comp's descriptor set uses (render_bindings.glsl), by kind.
struct BindingCounts {
    std::uint32_t texel = 0, storage = 0, uniform = 0;
};
constexpr BindingCounts kBindings = [] {
    BindingCounts c;
#define TEXEL_BINDING(binding, name, format, access) ++c.texel;
#define STORAGE_BINDING(binding, name, access) ++c.storage;
#define UNIFORM_BINDING(binding, name) ++c.uniform;
#include "render_bindings.glsl"
    return c;
}();

constexpr std::uint32_t kParamsBytes = sizeof(kernel::Params);

// The specification's guaranteed limits (Vulkan 1.1, "Required Limits"): the least a
// conforming device reports. Neither memory that is both device-local and
// host-visible, timestamps on the compute queue nor buffer device addresses (a
// Vulkan 1.2 feature) is guaranteed.
constexpr DeviceLimits kMinimum{
    .storage_images = 4,
    .storage_buffers = 4,
    .uniform_buffers = 12,
    .resources = 128,
    .texel_elements = 65536,
    .storage_range = std::uint64_t(1) << 27,
    .uniform_range = 16384,
    .push_constant_bytes = 128,
    .texel_offset_alignment = 256,
    .workgroup_count_x = 65535,
    .workgroup_count_y = 65535,
    .workgroup_invocations = 128,
    .workgroup_size_x = 128,
    .workgroup_size_y = 128,
    .allocation_bytes = std::uint64_t(1) << 30,
    .mapped_device_memory = false,
    .timestamps = false,
    .buffer_device_address = false,
};

// MoltenVK on an Apple M1 under macOS: derived from MoltenVK's MVKDevice.mm (the
// limits it computes from Metal's for Apple GPUs) and checked against published
// vulkaninfo reports of M1 machines; maxMemoryAllocationSize at the specification's
// minimum (not checked against the driver).
constexpr DeviceLimits kMoltenVkM1{
    .storage_images = 8,
    .storage_buffers = 31,
    .uniform_buffers = 31,
    .resources = 159,
    .texel_elements = 67108864,
    .storage_range = 4294967295u,
    .uniform_range = 4294967295u,
    .push_constant_bytes = 4096,
    .texel_offset_alignment = 16,
    .workgroup_count_x = 1073741824,
    .workgroup_count_y = 1073741824,
    .workgroup_invocations = 1024,
    .workgroup_size_x = 1024,
    .workgroup_size_y = 1024,
    .allocation_bytes = std::uint64_t(1) << 30,
    .mapped_device_memory = true,
    .timestamps = true,
    .buffer_device_address = true,
};

// Mesa's turnip on a Qualcomm Adreno 6xx (a mobile GPU): the constants of turnip's
// tu_device.cc and tu_common.h (which offers VK_KHR_buffer_device_address);
// maxMemoryAllocationSize at the specification's minimum (not checked against the
// driver). Qualcomm's own Android driver reports other values.
constexpr DeviceLimits kTurnipAdreno6xx{
    .storage_images = 16777216,
    .storage_buffers = 16777216,
    .uniform_buffers = 16777216,
    .resources = 16777216,
    .texel_elements = 134217728,
    .storage_range = 134217728,
    .uniform_range = 65536,
    .push_constant_bytes = 128,
    .texel_offset_alignment = 64,
    .workgroup_count_x = 65535,
    .workgroup_count_y = 65535,
    .workgroup_invocations = 1024,
    .workgroup_size_x = 1024,
    .workgroup_size_y = 1024,
    .allocation_bytes = std::uint64_t(1) << 30,
    .mapped_device_memory = true,
    .timestamps = true,
    .buffer_device_address = true,
};

const std::array kProfiles{
    DeviceProfile{"minimum", "every limit at the Vulkan specification's guaranteed minimum", kMinimum},
    DeviceProfile{"moltenvk-m1", "MoltenVK on an Apple M1 (macOS), from MoltenVK's MVKDevice.mm", kMoltenVkM1},
    DeviceProfile{"turnip-adreno6xx", "Mesa turnip on a Qualcomm Adreno 6xx, from turnip's tu_device.cc",
                  kTurnipAdreno6xx},
};

}  // namespace

DeviceLimits clamp_to(const DeviceLimits& d, const DeviceLimits& p) {
    DeviceLimits c;
    c.storage_images = std::min(d.storage_images, p.storage_images);
    c.storage_buffers = std::min(d.storage_buffers, p.storage_buffers);
    c.uniform_buffers = std::min(d.uniform_buffers, p.uniform_buffers);
    c.resources = std::min(d.resources, p.resources);
    c.texel_elements = std::min(d.texel_elements, p.texel_elements);
    c.storage_range = std::min(d.storage_range, p.storage_range);
    c.uniform_range = std::min(d.uniform_range, p.uniform_range);
    c.push_constant_bytes = std::min(d.push_constant_bytes, p.push_constant_bytes);
    c.texel_offset_alignment = std::max(d.texel_offset_alignment, p.texel_offset_alignment);
    c.workgroup_count_x = std::min(d.workgroup_count_x, p.workgroup_count_x);
    c.workgroup_count_y = std::min(d.workgroup_count_y, p.workgroup_count_y);
    c.workgroup_invocations = std::min(d.workgroup_invocations, p.workgroup_invocations);
    c.workgroup_size_x = std::min(d.workgroup_size_x, p.workgroup_size_x);
    c.workgroup_size_y = std::min(d.workgroup_size_y, p.workgroup_size_y);
    c.allocation_bytes = std::min(d.allocation_bytes, p.allocation_bytes);
    c.mapped_device_memory = d.mapped_device_memory && p.mapped_device_memory;
    c.timestamps = d.timestamps && p.timestamps;
    c.buffer_device_address = d.buffer_device_address && p.buffer_device_address;
    return c;
}

std::string missing(const DeviceLimits& l) {
    std::string out;
    auto need = [&](bool ok, const std::string& what) {
        if (!ok) out += (out.empty() ? "" : ", ") + what;
    };
    const std::uint32_t descriptors = kBindings.texel + kBindings.storage + kBindings.uniform;
    need(l.storage_images >= kBindings.texel, std::to_string(kBindings.texel) + " storage texel buffers");
    need(l.storage_buffers >= kBindings.storage, std::to_string(kBindings.storage) + " storage buffers");
    need(l.uniform_buffers >= kBindings.uniform, std::to_string(kBindings.uniform) + " uniform buffer");
    need(l.resources >= descriptors, std::to_string(descriptors) + " resources");
    need(l.texel_elements >= kParamsBytes / 16 && l.uniform_range >= kParamsBytes,
         "buffers of " + std::to_string(kParamsBytes) + " bytes");
    need(l.push_constant_bytes >= kPushBytes, std::to_string(kPushBytes) + " bytes of push constants");
    need(l.workgroup_invocations >= kWorkgroupSide * kWorkgroupSide && l.workgroup_size_x >= kWorkgroupSide &&
             l.workgroup_size_y >= kWorkgroupSide,
         "8x8 workgroups");
    if (!out.empty()) out += " in one compute stage";
    return out;
}

std::string format_limits(const DeviceLimits& l) {
    std::string out;
    auto line = [&](const char* vulkan_name, const std::string& value) {
        out += "  " + std::string(vulkan_name) + std::string(44 - std::string(vulkan_name).size(), ' ') + value + "\n";
    };
    auto yes_no = [](bool b) { return std::string(b ? "yes" : "no"); };
    line("maxPerStageDescriptorStorageImages", std::to_string(l.storage_images));
    line("maxPerStageDescriptorStorageBuffers", std::to_string(l.storage_buffers));
    line("maxPerStageDescriptorUniformBuffers", std::to_string(l.uniform_buffers));
    line("maxPerStageResources", std::to_string(l.resources));
    line("maxTexelBufferElements", std::to_string(l.texel_elements));
    line("maxStorageBufferRange", std::to_string(l.storage_range));
    line("maxUniformBufferRange", std::to_string(l.uniform_range));
    line("maxPushConstantsSize", std::to_string(l.push_constant_bytes));
    line("minTexelBufferOffsetAlignment", std::to_string(l.texel_offset_alignment));
    line("maxComputeWorkGroupCount[0], [1]",
         std::to_string(l.workgroup_count_x) + ", " + std::to_string(l.workgroup_count_y));
    line("maxComputeWorkGroupInvocations", std::to_string(l.workgroup_invocations));
    line("maxComputeWorkGroupSize[0], [1]",
         std::to_string(l.workgroup_size_x) + ", " + std::to_string(l.workgroup_size_y));
    line("maxMemoryAllocationSize", std::to_string(l.allocation_bytes));
    line("memory both device-local and host-visible", yes_no(l.mapped_device_memory));
    line("timestamps on the compute queue", yes_no(l.timestamps));
    line("bufferDeviceAddress", yes_no(l.buffer_device_address));
    return out;
}

std::span<const DeviceProfile> device_profiles() { return kProfiles; }

const DeviceProfile& find_profile(std::string_view name) {
    std::string names;
    for (const DeviceProfile& p : kProfiles) {
        if (p.name == name) return p;
        names += (names.empty() ? "" : ", ") + std::string(p.name);
    }
    throw GpuError("no device profile '" + std::string(name) + "'; profiles: " + names);
}

}  // namespace vkrt::gpu
