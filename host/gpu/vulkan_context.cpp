#include "gpu/vulkan_context.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gpu/portability.hpp"
#include "gpu/vulkan_devices.hpp"

namespace vkrt::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    static_cast<std::atomic<std::uint32_t>*>(user)->fetch_add(1);
    std::fprintf(stderr, "vulkan validation: %s\n", data && data->pMessage ? data->pMessage : "");
    // VK_FALSE: report only; aborting the call is the layer's business, not ours.
    return VK_FALSE;
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
    const InstanceSetup setup = instance_setup(offered_instance_extensions(), validation);
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pApplicationInfo = &app;
    info.flags = setup.flags;
    info.enabledExtensionCount = static_cast<std::uint32_t>(setup.extensions.size());
    info.ppEnabledExtensionNames = setup.extensions.data();
    if (validation) {
        // The messenger rides along so that instance creation and destruction are
        // checked too.
        info.pNext = &features;
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = layers;
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

VulkanContext::VulkanContext(const VulkanOptions& options) : instance_(options.validation), options_(options) {
    if (options_.profile.empty()) {
        const char* profile = std::getenv("VKRT_DEVICE_PROFILE");
        options_.profile = profile ? profile : "";
    }
    devices_ = instance_.devices();
    if (!options_.profile.empty()) {
        const DeviceProfile& profile = find_profile(options_.profile);
        for (PhysicalDevice& d : devices_) d.limits = clamp_to(d.limits, profile.limits);
    }
    const PhysicalDevice& chosen = select_device(devices_, options_.device);
    physical_ = chosen.handle;
    device_index_ = chosen.info.index;
    limits_ = chosen.limits;
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
    const std::vector<VkQueueFamilyProperties> families = queue_families(physical_);
    queue_family_ = compute_family(families);
    timestamp_bits_ = families[queue_family_].timestampValidBits;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    const std::vector<const char*> extensions = device_extensions(offered_device_extensions(physical_));
    VkDeviceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkPhysicalDeviceVulkan12Features v12{};
    v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    v12.bufferDeviceAddress = VK_TRUE;
    if (limits_.buffer_device_address) {
        info.pNext = &v12;
    }
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
    pipeline_cache_ = std::make_unique<PipelineCache>(device_, properties_, cache_dir_);
}

VulkanContext::~VulkanContext() {
    // Nothing may still run on the device when its objects go; a failure here has
    // nowhere to be reported, and destruction proceeds regardless.
    (void)vkDeviceWaitIdle(device_);
    pipeline_cache_.reset();
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
    if (++submissions_ == options_.lose_device_at_submission) {
        check(VK_ERROR_DEVICE_LOST, "vkWaitForFences (VulkanOptions::lose_device_at_submission)");
    }
}

}  // namespace vkrt::gpu
