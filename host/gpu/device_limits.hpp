#pragma once
// What the renderer relies on of a device, in one struct: device selection checks it
// (vulkan_devices.cpp), the data paths are planned from it (data_paths.hpp), and a
// profile clamps it to the specification's guaranteed minimum or to a documented
// real device, so that lavapipe can stand in for them (docs/porting.md). No Vulkan
// here, so the tests can drive it.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace vkrt::gpu {

struct DeviceLimits {
    // Descriptors one compute stage may use (the lesser of the per-stage and per-set
    // limits). Storage texel buffers count as storage images.
    std::uint32_t storage_images = 0;
    std::uint32_t storage_buffers = 0;
    std::uint32_t uniform_buffers = 0;
    std::uint32_t resources = 0;                // maxPerStageResources
    std::uint32_t texel_elements = 0;           // maxTexelBufferElements
    std::uint64_t storage_range = 0;            // maxStorageBufferRange, bytes
    std::uint32_t uniform_range = 0;            // maxUniformBufferRange, bytes
    std::uint32_t push_constant_bytes = 0;      // maxPushConstantsSize
    std::uint32_t texel_offset_alignment = 0;   // minTexelBufferOffsetAlignment, bytes
    std::uint32_t workgroup_count_x = 0;        // maxComputeWorkGroupCount[0]
    std::uint32_t workgroup_count_y = 0;        // maxComputeWorkGroupCount[1]
    std::uint32_t workgroup_invocations = 0;    // maxComputeWorkGroupInvocations
    std::uint32_t workgroup_size_x = 0;         // maxComputeWorkGroupSize[0]
    std::uint32_t workgroup_size_y = 0;         // maxComputeWorkGroupSize[1]
    std::uint64_t allocation_bytes = 0;         // maxMemoryAllocationSize
    bool mapped_device_memory = false;          // a memory type device-local and host-visible
    bool timestamps = false;                    // the compute queue writes timestamps
    // bufferDeviceAddress (Vulkan 1.2): the scene may be read through a pointer, so
    // that maxStorageBufferRange does not cap it (data_paths.hpp).
    bool buffer_device_address = false;
};

// Every limit at its worst of the two: a device clamped to a profile.
DeviceLimits clamp_to(const DeviceLimits& device, const DeviceLimits& profile);

// What the renderer needs that `limits` lacks, as a phrase for an error message;
// empty when the device can run it.
std::string missing(const DeviceLimits& limits);

// One line per limit, with the Vulkan name it comes from: `vkrt devices --limits`.
std::string format_limits(const DeviceLimits& limits);

// A named set of limits to clamp a device to (VulkanOptions::profile).
struct DeviceProfile {
    std::string_view name;
    std::string_view description;  // what it stands for, and where the values come from
    DeviceLimits limits;
};

std::span<const DeviceProfile> device_profiles();
// The profile of that name; throws GpuError listing the names when there is none.
const DeviceProfile& find_profile(std::string_view name);

}  // namespace vkrt::gpu
