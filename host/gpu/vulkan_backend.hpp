#pragma once
// The Vulkan compute backend. This header is Vulkan-free on purpose: only the .cpp
// files of host/gpu/ include vulkan.h (docs/architecture.md).
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gpu/data_paths.hpp"
#include "gpu/gpu_error.hpp"
#include "render/backend.hpp"

namespace vkrt {

struct VulkanOptions {
    // VulkanOptions{device, validation}: the two fields most callers set.
    explicit VulkanOptions(std::string device_ = {}, bool validation_ = false)
        : device(std::move(device_)), validation(validation_) {}

    // Empty: the first discrete GPU, else integrated, else any (lavapipe last resort).
    // A number: that index in `vkrt devices`. Otherwise a case-insensitive substring
    // of the device or driver name; "lavapipe" also matches Mesa's llvmpipe driver.
    std::string device;
    // Enable VK_LAYER_KHRONOS_validation and count (and print) every message.
    bool validation = false;
    // Plan as if the device had no more than a profile's limits (gpu/device_limits.hpp,
    // docs/porting.md): "minimum" for the specification's. Empty: VKRT_DEVICE_PROFILE,
    // else the device's own.
    std::string profile;
    // Force a data path instead of the device's choice (gpu/data_paths.hpp): tests.
    gpu::PathChoice scene_path = gpu::PathChoice::Automatic;
    gpu::PathChoice params_path = gpu::PathChoice::Automatic;
    // The bound on one queue submission's time, which tiles and batches are planned
    // to stay under (a GPU watchdog fires at 2 s on Windows). 0: the default.
    double submit_bound_seconds = 0.0;
    // Tests: report the device lost after this many submissions (0: never), as a
    // driver reset would.
    std::uint32_t lose_device_at_submission = 0;
};

struct DeviceInfo {
    std::uint32_t index = 0;
    std::string name;
    std::string type;    // "discrete", "integrated", "virtual", "cpu", "other"
    std::string driver;  // driver name and info, e.g. "llvmpipe Mesa 22.3.6"
    std::string api_version;
};

std::vector<DeviceInfo> list_vulkan_devices();

// For each device: the limits the renderer relies on (clamped to the profile of that
// name when one is given), whether it can run vkrt, and the heuristics it gets
// (gpu/device_class.hpp). `vkrt devices --limits`: what to send back when a device
// fails (docs/porting.md).
std::string device_limits_report(const std::string& profile);
std::unique_ptr<Backend> make_vulkan_backend(const VulkanOptions& options);

}  // namespace vkrt
