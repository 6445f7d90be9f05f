#pragma once
// The float probe on Vulkan devices: shaders/float_probe.comp dispatched once over
// probe_cases() (docs/numerics.md). Vulkan-free, like vulkan_backend.hpp.
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "gpu/vulkan_backend.hpp"

namespace vkrt {

struct DeviceProbeRun {
    std::string device;                // the device's name
    std::vector<glm::vec4> results;    // one per case of probe::probe_cases()
};

// Runs the probe on the device `options.device` selects (as render's --device does),
// or, when it is empty, on every device that can run vkrt, in `vkrt devices` order.
// With options.validation, any validation message is an error.
std::vector<DeviceProbeRun> run_vulkan_float_probe(const VulkanOptions& options);

}  // namespace vkrt
