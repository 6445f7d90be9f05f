#include "gpu/vulkan_context.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace vkrt::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr const char* kNoDriverHint =
    "no usable Vulkan driver; install one (on Debian/Ubuntu, mesa-vulkan-drivers provides "
    "lavapipe, a Vulkan device that runs on the CPU), or render with --backend cpu";

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    static_cast<std::atomic<std::uint32_t>*>(user)->fetch_add(1);
    std::fprintf(stderr, "vulkan validation: %s\n", data && data->pMessage ? data->pMessage : "");
    // VK_FALSE: report only; aborting the call is the layer's business, not ours.
    return VK_FALSE;
}

// The second call of an enumeration may find more entries than the first counted
// (a device or layer appeared in between); the shorter list is still a good answer.
void check_listing(VkResult result, const char* call) {
    if (result != VK_INCOMPLETE) {
        check(result, call);
    }
}

bool has_layer(const char* name) {
    std::uint32_t count = 0;
    check(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
    std::vector<VkLayerProperties> layers(count);
    check_listing(vkEnumerateInstanceLayerProperties(&count, layers.data()),
                  "vkEnumerateInstanceLayerProperties");
    return std::any_of(layers.begin(), layers.begin() + count,
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool has_device_extension(VkPhysicalDevice device, const char* name) {
    std::uint32_t count = 0;
    check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr),
          "vkEnumerateDeviceExtensionProperties");
    std::vector<VkExtensionProperties> extensions(count);
    check_listing(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()),
                  "vkEnumerateDeviceExtensionProperties");
    return std::any_of(extensions.begin(), extensions.begin() + count,
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
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
    return d.has_compute && d.api_version >= VK_API_VERSION_1_1;
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

// A family that does compute but not graphics is preferred: on GPUs it is the queue
// least likely to share time with the desktop.
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

std::vector<VkQueueFamilyProperties> queue_families(VkPhysicalDevice device) {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    families.resize(count);
    return families;
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

std::string result_name(VkResult result) {
    switch (result) {
#define VKRT_RESULT(name) case name: return #name;
        VKRT_RESULT(VK_SUCCESS)
        VKRT_RESULT(VK_NOT_READY)
        VKRT_RESULT(VK_TIMEOUT)
        VKRT_RESULT(VK_EVENT_SET)
        VKRT_RESULT(VK_EVENT_RESET)
        VKRT_RESULT(VK_INCOMPLETE)
        VKRT_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        VKRT_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        VKRT_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        VKRT_RESULT(VK_ERROR_DEVICE_LOST)
        VKRT_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        VKRT_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        VKRT_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        VKRT_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        VKRT_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        VKRT_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        VKRT_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        VKRT_RESULT(VK_ERROR_FRAGMENTED_POOL)
        VKRT_RESULT(VK_ERROR_UNKNOWN)
        VKRT_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        VKRT_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        VKRT_RESULT(VK_ERROR_FRAGMENTATION)
        VKRT_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        VKRT_RESULT(VK_PIPELINE_COMPILE_REQUIRED)
        VKRT_RESULT(VK_ERROR_VALIDATION_FAILED_EXT)
#undef VKRT_RESULT
        default: return "VkResult " + std::to_string(static_cast<int>(result));
    }
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
    VkMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

VulkanInstance::VulkanInstance(bool validation) {
    // A 1.0 loader cannot make the 1.1 instance that vkGetPhysicalDeviceProperties2
    // and the rest of this backend need.
    std::uint32_t loader_version = VK_API_VERSION_1_0;
    if (vkEnumerateInstanceVersion(&loader_version) != VK_SUCCESS || loader_version < VK_API_VERSION_1_1) {
        throw GpuError(std::string("Vulkan 1.1 is not available: ") + kNoDriverHint);
    }
    // 1.2 where the loader has it, so driver properties are core; 1.1 is enough otherwise.
    api_version_ = loader_version >= VK_API_VERSION_1_2 ? VK_API_VERSION_1_2 : VK_API_VERSION_1_1;

    if (validation && !has_layer(kValidationLayer)) {
        throw GpuError(std::string("validation requested but ") + kValidationLayer +
                       " is not installed (on Debian/Ubuntu: vulkan-validationlayers)");
    }

    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "vkrt";
    app.pEngineName = "vkrt";
    app.apiVersion = api_version_;

    // Warnings and errors only: info and verbose messages are chatter, not findings.
    VkDebugUtilsMessengerCreateInfoEXT messenger{};
    messenger.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = on_validation_message;
    messenger.pUserData = &messages_;

    // Synchronization validation too: the core checks do not see a missing barrier
    // between a fill or copy and the dispatches that use the buffer. (Layer 1.3.239
    // does not flag two dispatches writing the same bound buffer, though, so the
    // barrier between samples is on us.)
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{};
    features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
    features.pNext = &messenger;
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;

    const char* layers[] = {kValidationLayer};
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pApplicationInfo = &app;
    if (validation) {
        // The messenger rides along so that instance creation and destruction are
        // checked too.
        info.pNext = &features;
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = layers;
        info.enabledExtensionCount = 2;
        info.ppEnabledExtensionNames = extensions;
    }
    const VkResult created = vkCreateInstance(&info, nullptr, &instance_);
    if (created == VK_ERROR_INCOMPATIBLE_DRIVER || created == VK_ERROR_INITIALIZATION_FAILED) {
        throw GpuError("vkCreateInstance failed: " + result_name(created) + ": " + kNoDriverHint);
    }
    check(created, "vkCreateInstance");

    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        const VkResult made = create ? create(instance_, &messenger, nullptr, &messenger_)
                                     : VK_ERROR_EXTENSION_NOT_PRESENT;
        if (made != VK_SUCCESS) {
            vkDestroyInstance(instance_, nullptr);
            check(made, "vkCreateDebugUtilsMessengerEXT");
        }
    }
}

VulkanInstance::~VulkanInstance() {
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) {
            destroy(instance_, messenger_, nullptr);
        }
    }
    vkDestroyInstance(instance_, nullptr);
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
            throw GpuError("no Vulkan device supports Vulkan 1.1 with a compute queue; available: " +
                           describe_all(devices));
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
        throw GpuError("Vulkan device " + describe(*chosen) +
                       " cannot run vkrt: it needs Vulkan 1.1 and a compute queue");
    }
    return *chosen;
}

VulkanContext::VulkanContext(const VulkanOptions& options) : instance_(options.validation) {
    const std::vector<PhysicalDevice> devices = instance_.devices();
    const PhysicalDevice& chosen = select_device(devices, options.device);
    physical_ = chosen.handle;
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
    const std::vector<VkQueueFamilyProperties> families = queue_families(physical_);
    queue_family_ = compute_family(families);
    timestamp_bits_ = families[queue_family_].timestampValidBits;
    const char* staging = std::getenv("VKRT_VULKAN_FORCE_STAGING");
    force_staging_ = staging && std::strcmp(staging, "1") == 0;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    check(vkCreateDevice(physical_, &info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool.queueFamilyIndex = queue_family_;
    const VkResult made = vkCreateCommandPool(device_, &pool, nullptr, &pool_);
    if (made != VK_SUCCESS) {
        // The destructor does not run for a half-built object.
        vkDestroyDevice(device_, nullptr);
        check(made, "vkCreateCommandPool");
    }
}

VulkanContext::~VulkanContext() {
    // Nothing may still run on the device when its objects go; a failure here has
    // nowhere to be reported, and destruction proceeds regardless.
    (void)vkDeviceWaitIdle(device_);
    vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
}

void VulkanContext::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(device_, &alloc, &cmd), "vkAllocateCommandBuffers");
    struct Release {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~Release() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } release{device_, pool_, cmd};

    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    record(cmd);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence raw_fence = VK_NULL_HANDLE;
    check(vkCreateFence(device_, &fence_info, nullptr, &raw_fence), "vkCreateFence");
    DeviceHandle<VkFence, vkDestroyFence> fence(device_, raw_fence);

    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    check(vkQueueSubmit(queue_, 1, &submit, fence.get()), "vkQueueSubmit");
    check(vkWaitForFences(device_, 1, &raw_fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

}  // namespace vkrt::gpu
