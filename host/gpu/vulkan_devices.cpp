#include "gpu/vulkan_devices.hpp"

#include "gpu/portability.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "gpu/vulkan_context.hpp"
#include "gpu/device_class.hpp"
#include "gpu/vulkan_pipeline.hpp"

namespace vkrt::gpu {

void check_listing(VkResult result, const char* call) {
    if (result != VK_INCOMPLETE) {
        check(result, call);
    }
}

std::vector<VkQueueFamilyProperties> queue_families(VkPhysicalDevice device) {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    families.resize(count);
    return families;
}

std::uint32_t compute_family(const std::vector<VkQueueFamilyProperties>& families) {
    std::uint32_t best = UINT32_MAX;
    for (std::uint32_t i = 0; i < families.size(); ++i) {
        const VkQueueFlags flags = families[i].queueFlags;
        if ((flags & VK_QUEUE_COMPUTE_BIT) == 0 || families[i].queueCount == 0) {
            continue;
        }
        if ((flags & VK_QUEUE_GRAPHICS_BIT) == 0) {
            return i;
        }
        best = std::min(best, i);
    }
    return best;
}

namespace {

bool has_device_extension(VkPhysicalDevice device, const char* name) {
    return offers(offered_device_extensions(device), name);
}

std::string type_name(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        default: return "other";
    }
}

// Lower is better when no device was named.
int type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

std::string version_string(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

bool usable(const PhysicalDevice& d) {
    return d.has_compute && d.api_version >= VK_API_VERSION_1_1 && missing(d.limits).empty();
}

// Why `d` cannot run vkrt.
std::string needs(const PhysicalDevice& d) {
    std::string out = "it needs Vulkan 1.1 and a compute queue";
    const std::string lacks = missing(d.limits);
    if (!lacks.empty()) out += ", and " + lacks;
    return out;
}

std::string describe(const PhysicalDevice& d) {
    return std::to_string(d.info.index) + ": " + d.info.name + " [" + d.info.type + ", " +
           d.info.driver + "]";
}

std::string describe_all(const std::vector<PhysicalDevice>& devices) {
    std::string out;
    for (const PhysicalDevice& d : devices) {
        out += (out.empty() ? "" : "; ") + describe(d);
    }
    return out;
}

bool matches(const PhysicalDevice& d, const std::string& selector) {
    const std::string s = lower(selector);
    if (lower(d.info.name).find(s) != std::string::npos ||
        lower(d.info.driver).find(s) != std::string::npos) {
        return true;
    }
    // Mesa calls its Vulkan CPU driver lavapipe but reports it as llvmpipe.
    return d.driver_id == VK_DRIVER_ID_MESA_LLVMPIPE && std::string("lavapipe").find(s) != std::string::npos;
}

PhysicalDevice describe_device(VkPhysicalDevice handle, std::uint32_t index,
                               std::uint32_t instance_api) {
    PhysicalDevice d;
    d.handle = handle;
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(handle, &props);
    d.type = props.deviceType;
    d.api_version = props.apiVersion;
    d.info.index = index;
    d.info.name = props.deviceName;
    d.info.type = type_name(props.deviceType);
    d.info.api_version = version_string(props.apiVersion);
    d.info.driver = "unknown driver";
    d.limits = read_limits(handle, instance_api);

    // Driver properties are core from 1.2 (as both sides see it), else an extension.
    const std::uint32_t effective = std::min(instance_api, props.apiVersion);
    if (effective >= VK_API_VERSION_1_2 ||
        (effective >= VK_API_VERSION_1_1 && has_device_extension(handle, VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME))) {
        VkPhysicalDeviceDriverProperties driver{};
        driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
        VkPhysicalDeviceProperties2 props2{};
        props2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
        props2.pNext = &driver;
        vkGetPhysicalDeviceProperties2(handle, &props2);
        d.driver_id = driver.driverID;
        d.info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    }
    d.has_compute = compute_family(queue_families(handle)) != UINT32_MAX;
    return d;
}

}  // namespace

DeviceLimits read_limits(VkPhysicalDevice device, std::uint32_t instance_api) {
    VkPhysicalDeviceMaintenance3Properties maintenance3{};
    maintenance3.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES;
    VkPhysicalDeviceProperties2 props2{};
    props2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    props2.pNext = &maintenance3;
    vkGetPhysicalDeviceProperties2(device, &props2);
    const VkPhysicalDeviceProperties& props = props2.properties;
    const VkPhysicalDeviceLimits& l = props.limits;
    DeviceLimits d;
    d.storage_images = std::min(l.maxPerStageDescriptorStorageImages, l.maxDescriptorSetStorageImages);
    d.storage_buffers = std::min(l.maxPerStageDescriptorStorageBuffers, l.maxDescriptorSetStorageBuffers);
    d.uniform_buffers = std::min(l.maxPerStageDescriptorUniformBuffers, l.maxDescriptorSetUniformBuffers);
    d.resources = l.maxPerStageResources;
    d.texel_elements = l.maxTexelBufferElements;
    d.storage_range = l.maxStorageBufferRange;
    d.uniform_range = l.maxUniformBufferRange;
    d.push_constant_bytes = l.maxPushConstantsSize;
    d.texel_offset_alignment = std::uint32_t(l.minTexelBufferOffsetAlignment);
    d.workgroup_count_x = l.maxComputeWorkGroupCount[0];
    d.workgroup_count_y = l.maxComputeWorkGroupCount[1];
    d.workgroup_invocations = l.maxComputeWorkGroupInvocations;
    d.workgroup_size_x = l.maxComputeWorkGroupSize[0];
    d.workgroup_size_y = l.maxComputeWorkGroupSize[1];
    d.allocation_bytes = maintenance3.maxMemoryAllocationSize;
    // As a Vulkan 1.2 feature only, so that one create-info enables it (vulkan_context.cpp).
    if (std::min(instance_api, props.apiVersion) >= VK_API_VERSION_1_2) {
        VkPhysicalDeviceVulkan12Features v12{};
        v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
        VkPhysicalDeviceFeatures2 features{};
        features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
        features.pNext = &v12;
        vkGetPhysicalDeviceFeatures2(device, &features);
        d.buffer_device_address = v12.bufferDeviceAddress == VK_TRUE;
    }
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(device, &memory);
    const VkMemoryPropertyFlags mapped = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        d.mapped_device_memory = d.mapped_device_memory || (memory.memoryTypes[i].propertyFlags & mapped) == mapped;
    }
    const std::vector<VkQueueFamilyProperties> families = queue_families(device);
    const std::uint32_t family = compute_family(families);
    d.timestamps = family != UINT32_MAX && families[family].timestampValidBits > 0 && l.timestampPeriod > 0.0f;
    return d;
}

std::vector<PhysicalDevice> VulkanInstance::devices() const {
    std::uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance_, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> handles(count);
    check_listing(vkEnumeratePhysicalDevices(instance_, &count, handles.data()), "vkEnumeratePhysicalDevices");
    std::vector<PhysicalDevice> devices;
    for (std::uint32_t i = 0; i < count; ++i) {
        devices.push_back(describe_device(handles[i], i, api_version_));
    }
    return devices;
}

const PhysicalDevice* device_for_scene(const std::vector<PhysicalDevice>& devices, const DataSizes& sizes) {
    const PhysicalDevice* best = nullptr;
    for (const PhysicalDevice& d : devices) {
        if (!usable(d) || (best && type_rank(d.type) >= type_rank(best->type))) continue;
        try {
            plan_data_paths(d.limits, d.type == VK_PHYSICAL_DEVICE_TYPE_CPU, sizes);
            best = &d;
        } catch (const SceneDoesNotFit&) {
        }
    }
    return best;
}

const PhysicalDevice& select_device(const std::vector<PhysicalDevice>& devices,
                                    const std::string& selector) {
    if (devices.empty()) {
        throw GpuError(std::string("no Vulkan device found: ") + kNoDriverHint);
    }
    const PhysicalDevice* chosen = nullptr;
    if (selector.empty()) {
        for (const PhysicalDevice& d : devices) {
            if (usable(d) && (!chosen || type_rank(d.type) < type_rank(chosen->type))) {
                chosen = &d;
            }
        }
        if (!chosen) {
            std::string why;
            for (const PhysicalDevice& d : devices) why += (why.empty() ? "" : "; ") + describe(d) + ": " + needs(d);
            throw GpuError("no Vulkan device can run vkrt (" + why + ")");
        }
        return *chosen;
    }
    const bool is_index = std::all_of(selector.begin(), selector.end(),
                                      [](unsigned char c) { return std::isdigit(c) != 0; });
    if (is_index) {
        const unsigned long index = std::strtoul(selector.c_str(), nullptr, 10);
        if (index < devices.size()) {
            chosen = &devices[index];
        }
    } else {
        auto found = std::find_if(devices.begin(), devices.end(),
                                  [&](const PhysicalDevice& d) { return matches(d, selector); });
        if (found != devices.end()) {
            chosen = &*found;
        }
    }
    if (!chosen) {
        throw GpuError("no Vulkan device matches '" + selector + "'; available: " + describe_all(devices));
    }
    if (!usable(*chosen)) {
        throw GpuError("Vulkan device " + describe(*chosen) + " cannot run vkrt: " + needs(*chosen));
    }
    return *chosen;
}

}  // namespace vkrt::gpu

namespace vkrt {

std::vector<DeviceInfo> list_vulkan_devices() {
    const gpu::VulkanInstance instance(false);
    std::vector<DeviceInfo> infos;
    for (const gpu::PhysicalDevice& d : instance.devices()) {
        infos.push_back(d.info);
    }
    return infos;
}

namespace {

std::string seconds_text(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", seconds);
    return text;
}

}  // namespace

std::string device_limits_report(const std::string& profile) {
    const gpu::VulkanInstance instance(false);
    const gpu::DeviceProfile* clamp = profile.empty() ? nullptr : &gpu::find_profile(profile);
    std::string out;
    for (gpu::PhysicalDevice d : instance.devices()) {
        if (clamp) d.limits = gpu::clamp_to(d.limits, clamp->limits);
        out += gpu::describe(d) + (clamp ? " as profile " + profile : std::string()) + "\n";
        out += gpu::format_limits(d.limits);
        out += "  can run vkrt: " + (gpu::usable(d) ? std::string("yes") : "no, " + gpu::needs(d)) + "\n";
        const gpu::DeviceHeuristics h = gpu::heuristics_for(d.type == VK_PHYSICAL_DEVICE_TYPE_CPU);
        out += "  heuristics (" + h.name + "): submissions planned under " + seconds_text(h.submit_bound_seconds) +
               ", grid from " + std::to_string(h.accel.brute_force_below) + " primitives, deferred sphere tests from " +
               std::to_string(h.accel.deferred_spheres_from) + " spheres" +
               (h.measured ? "" : " (lavapipe's values, unmeasured here: vkrt bench --threshold --device " +
                                      std::to_string(d.info.index) + " measures the grid's)") + "\n";
    }
    if (out.empty()) out = "no Vulkan devices\n";
    return out;
}

}  // namespace vkrt
