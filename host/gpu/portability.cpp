#include "gpu/portability.hpp"

#include <algorithm>

#include "gpu/vulkan_context.hpp"
#include "gpu/vulkan_devices.hpp"

namespace vkrt::gpu {
namespace {

// Spelled out: the macro lives in vulkan_beta.h, which a portable build need not include.
constexpr const char* kPortabilitySubset = "VK_KHR_portability_subset";

}  // namespace

bool offers(const std::vector<std::string>& offered, const char* name) {
    return std::find(offered.begin(), offered.end(), name) != offered.end();
}

InstanceSetup instance_setup(const std::vector<std::string>& offered, bool validation) {
    InstanceSetup setup;
    if (validation) {
        setup.extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        setup.extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }
    if (offers(offered, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
        setup.extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
        setup.flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
    }
    return setup;
}

std::vector<const char*> device_extensions(const std::vector<std::string>& offered) {
    std::vector<const char*> names;
    if (offers(offered, kPortabilitySubset)) names.push_back(kPortabilitySubset);
    return names;
}

std::vector<std::string> offered_instance_extensions() {
    std::uint32_t count = 0;
    check(vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr), "vkEnumerateInstanceExtensionProperties");
    std::vector<VkExtensionProperties> properties(count);
    check_listing(vkEnumerateInstanceExtensionProperties(nullptr, &count, properties.data()),
                  "vkEnumerateInstanceExtensionProperties");
    std::vector<std::string> names;
    for (std::uint32_t i = 0; i < count; ++i) names.emplace_back(properties[i].extensionName);
    return names;
}

std::vector<std::string> offered_device_extensions(VkPhysicalDevice device) {
    std::uint32_t count = 0;
    check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr),
          "vkEnumerateDeviceExtensionProperties");
    std::vector<VkExtensionProperties> properties(count);
    check_listing(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, properties.data()),
                  "vkEnumerateDeviceExtensionProperties");
    std::vector<std::string> names;
    for (std::uint32_t i = 0; i < count; ++i) names.emplace_back(properties[i].extensionName);
    return names;
}

}  // namespace vkrt::gpu
