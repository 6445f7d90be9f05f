#pragma once
// The Vulkan compute backend. This header is Vulkan-free on purpose: only the .cpp
// files of host/gpu/ include vulkan.h (docs/architecture.md).
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/backend.hpp"

namespace vkrt {

class GpuError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct VulkanOptions {
    // Empty: the first discrete GPU, else integrated, else any (lavapipe last resort).
    // A number: that index in `vkrt devices`. Otherwise a case-insensitive substring
    // of the device or driver name; "lavapipe" also matches Mesa's llvmpipe driver.
    std::string device;
    // Enable VK_LAYER_KHRONOS_validation and count (and print) every message.
    bool validation = false;
};

struct DeviceInfo {
    std::uint32_t index = 0;
    std::string name;
    std::string type;    // "discrete", "integrated", "virtual", "cpu", "other"
    std::string driver;  // driver name and info, e.g. "llvmpipe Mesa 22.3.6"
    std::string api_version;
};

std::vector<DeviceInfo> list_vulkan_devices();
std::unique_ptr<Backend> make_vulkan_backend(const VulkanOptions& options);

}  // namespace vkrt
