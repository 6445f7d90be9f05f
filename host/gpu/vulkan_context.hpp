#pragma once
// The Vulkan instance, the chosen physical device, its logical device, one compute
// queue and a command pool: everything a render needs that does not depend on the
// scene. Internal to host/gpu/ (the only folder that includes vulkan.h).
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/vulkan_backend.hpp"

namespace vkrt::gpu {

std::string result_name(VkResult result);

// Every VkResult goes through this: a failure becomes a GpuError naming the call.
inline void check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) {
        throw GpuError(std::string(call) + " failed: " + result_name(result));
    }
}

// Owns one device-level handle; destroyed with its vkDestroy* function. Move-only so
// the owner's member order alone decides the destruction order.
template <typename T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
class DeviceHandle {
public:
    DeviceHandle() = default;
    DeviceHandle(VkDevice device, T handle) : device_(device), handle_(handle) {}
    DeviceHandle(DeviceHandle&& other) noexcept
        : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
    DeviceHandle& operator=(DeviceHandle&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = other.device_;
            handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }
    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    ~DeviceHandle() { reset(); }

    T get() const { return handle_; }
    void reset() {
        if (handle_ != VK_NULL_HANDLE) {
            Destroy(device_, handle_, nullptr);
            handle_ = VK_NULL_HANDLE;
        }
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    T handle_ = VK_NULL_HANDLE;
};

// Records a global memory barrier: writes of `src_access` in `src_stage` become
// visible to accesses of `dst_access` in `dst_stage`.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

// A physical device as enumerated, with what selection needs to know about it.
struct PhysicalDevice {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    DeviceInfo info;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    VkDriverId driver_id{};  // 0 when the device cannot report it
    std::uint32_t api_version = 0;
    bool has_compute = false;
    // Storage texel buffers a compute shader may bind: the lesser of the per-stage and
    // per-set limits on storage images, which they count against.
    std::uint32_t storage_texel_buffers = 0;
};

// The instance and, when asked for, the validation layer's messenger. Not movable:
// the messenger callback holds a pointer to the message counter inside it.
class VulkanInstance {
public:
    explicit VulkanInstance(bool validation);
    ~VulkanInstance();
    VulkanInstance(const VulkanInstance&) = delete;
    VulkanInstance& operator=(const VulkanInstance&) = delete;

    VkInstance get() const { return instance_; }
    std::uint32_t api_version() const { return api_version_; }
    std::uint32_t validation_messages() const { return messages_.load(); }
    std::vector<PhysicalDevice> devices() const;

private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    std::uint32_t api_version_ = 0;
    std::atomic<std::uint32_t> messages_{0};
};

// The device chosen by `selector` (VulkanOptions::device) among `devices`.
const PhysicalDevice& select_device(const std::vector<PhysicalDevice>& devices,
                                    const std::string& selector);

class VulkanContext {
public:
    explicit VulkanContext(const VulkanOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkPhysicalDevice physical_device() const { return physical_; }
    VkDevice device() const { return device_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_; }
    std::uint32_t timestamp_valid_bits() const { return timestamp_bits_; }
    std::uint32_t validation_messages() const { return instance_.validation_messages(); }
    // Set by VKRT_VULKAN_FORCE_STAGING=1: take the staging path even where mapped
    // device memory exists, so CI (lavapipe has only mapped memory) exercises it.
    bool force_staging() const { return force_staging_; }

    // Records one command buffer, submits it to the compute queue and waits for it.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

private:
    VulkanInstance instance_;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    std::uint32_t queue_family_ = 0;
    std::uint32_t timestamp_bits_ = 0;
    bool force_staging_ = false;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
};

}  // namespace vkrt::gpu
