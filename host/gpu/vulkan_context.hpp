#pragma once
// The Vulkan instance, the chosen physical device, its logical device, one compute
// queue and a command pool: everything a render needs that does not depend on the
// scene. Internal to host/gpu/ (the only folder that includes vulkan.h).
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/device_limits.hpp"
#include "gpu/pipeline_cache.hpp"
#include "gpu/vulkan_backend.hpp"

namespace vkrt::gpu {

std::string result_name(VkResult result);

// VK_ERROR_DEVICE_LOST: the driver reset the device (a GPU watchdog, a driver fault);
// everything made on it is gone, and a new context may render again.
class DeviceLost : public GpuError {
public:
    using GpuError::GpuError;
};

// Every VkResult goes through this: a failure becomes a GpuError naming the call.
inline void check(VkResult result, const char* call) {
    if (result == VK_ERROR_DEVICE_LOST) {
        throw DeviceLost(std::string(call) + " failed: the Vulkan device was lost (VK_ERROR_DEVICE_LOST: a "
                         "driver reset, such as a GPU watchdog ending a long submission, or a driver fault)");
    }
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
    DeviceLimits limits;  // as the device reports them, or clamped to a profile
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

// What the renderer reads of a device's limits, features and memory
// (device_limits.hpp), as an instance of `instance_api` sees them.
DeviceLimits read_limits(VkPhysicalDevice device, std::uint32_t instance_api);

// Among the usable devices, the one select_device would prefer of those whose
// limits hold a scene of these sizes (data_paths.hpp); nullptr when none does.
const PhysicalDevice* device_for_scene(const std::vector<PhysicalDevice>& devices, const DataSizes& sizes);

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
    // The limits the renderer plans with: the device's, clamped to the profile of
    // VulkanOptions::profile (or VKRT_DEVICE_PROFILE) when one is named.
    const DeviceLimits& limits() const { return limits_; }
    const VulkanOptions& options() const { return options_; }
    // Every device of the instance, with its limits as the profile clamps them, and
    // the index of the one in use among them.
    const std::vector<PhysicalDevice>& devices() const { return devices_; }
    std::uint32_t device_index() const { return device_index_; }
    bool cpu_device() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
    // Valid bits of the compute queue's timestamps; 0 where the limits have none.
    std::uint32_t timestamp_valid_bits() const { return limits_.timestamps ? timestamp_bits_ : 0; }
    std::uint32_t validation_messages() const { return instance_.validation_messages(); }

    // The pipeline cache kept between runs (gpu/pipeline_cache.hpp); pipelines are
    // made through it, and save_pipeline_cache writes what they added.
    VkPipelineCache pipeline_cache() const { return pipeline_cache_->get(); }
    // Where that cache and the specialized SPIR-V live; empty: nowhere.
    const std::filesystem::path& cache_dir() const { return cache_dir_; }
    void save_pipeline_cache() const { pipeline_cache_->save(); }

    // Records one command buffer, submits it to the compute queue and waits for it.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

private:
    VulkanInstance instance_;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    std::uint32_t queue_family_ = 0;
    std::uint32_t timestamp_bits_ = 0;
    VulkanOptions options_;
    std::vector<PhysicalDevice> devices_;
    std::uint32_t device_index_ = 0;
    DeviceLimits limits_;
    mutable std::uint32_t submissions_ = 0;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::filesystem::path cache_dir_ = pipeline_cache_dir();
    std::unique_ptr<PipelineCache> pipeline_cache_;
};

}  // namespace vkrt::gpu
