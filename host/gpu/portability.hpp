#pragma once
// The extensions and flags that let vkrt see and use a portability implementation,
// such as MoltenVK over Metal: since loader 1.3.216 such drivers are listed only to an
// instance created with VK_KHR_portability_enumeration and its flag, and a device that
// advertises VK_KHR_portability_subset must have it enabled (Vulkan specification,
// "Portability Subset"). Pure functions of what the loader or device offers, so that
// the choices are tested without such a device.
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace vkrt::gpu {

struct InstanceSetup {
    std::vector<const char*> extensions;  // static strings
    VkInstanceCreateFlags flags = 0;
};

// What the instance enables, given the instance extensions the loader offers:
// validation's two extensions when asked, portability enumeration when offered.
InstanceSetup instance_setup(const std::vector<std::string>& offered, bool validation);

// Whether `name` is among the extensions `offered`.
bool offers(const std::vector<std::string>& offered, const char* name);

// What a device enables, given the device extensions it offers.
std::vector<const char*> device_extensions(const std::vector<std::string>& offered);

// The extensions the loader (and its implicit layers) offers, and a device's.
std::vector<std::string> offered_instance_extensions();
std::vector<std::string> offered_device_extensions(VkPhysicalDevice device);

}  // namespace vkrt::gpu
