#pragma once
// Helpers shared by vulkan_context.cpp and vulkan_devices.cpp (physical-device
// enumeration and selection). Internal to host/gpu/.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace vkrt::gpu {

inline constexpr const char* kNoDriverHint =
    "no usable Vulkan driver; install one (on Debian/Ubuntu, mesa-vulkan-drivers provides "
    "lavapipe, a Vulkan device that runs on the CPU), or render with --backend cpu";

// The second call of an enumeration may find more entries than the first counted
// (a device or layer appeared in between); the shorter list is still a good answer.
void check_listing(VkResult result, const char* call);

std::vector<VkQueueFamilyProperties> queue_families(VkPhysicalDevice device);

// The queue family to run compute on, or UINT32_MAX when there is none. A family
// that does compute but not graphics is preferred: on GPUs it is the queue least
// likely to share time with the desktop.
std::uint32_t compute_family(const std::vector<VkQueueFamilyProperties>& families);

}  // namespace vkrt::gpu
