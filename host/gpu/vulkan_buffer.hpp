#pragma once
// A buffer and its memory, with upload and read-back. Where the device has memory
// that is both device-local and host-mapped (lavapipe, integrated GPUs, resizable-BAR
// GPUs), the buffer is mapped once and copies are memcpy; otherwise it lives in
// device-local memory and copies go through a temporary staging buffer.
#include <cstdint>
#include <functional>
#include <string>

#include "gpu/vulkan_context.hpp"

namespace vkrt::gpu {

enum class Placement {
    Device,   // used by shaders: device-local, mapped when the device allows
    Staging,  // host-visible and coherent: the other end of a copy
    Readback, // host-visible and coherent, host-cached where the device has it: read by the CPU
};

class VulkanBuffer {
public:
    // `usage` is how shaders bind it (with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
    // how they reach it by address); transfer usage is added as the placement needs.
    // `name` appears in error messages.
    VulkanBuffer(const VulkanContext& context, std::string name, VkDeviceSize size,
                 VkBufferUsageFlags usage, Placement placement = Placement::Device);

    VkBuffer get() const { return buffer_.get(); }
    VkDeviceSize size() const { return size_; }
    bool mapped() const { return mapped_ != nullptr; }
    // Mapped memory the CPU reads through its caches (uncached reads are slow).
    bool host_cached() const { return mapped_ != nullptr && cached_; }
    const void* data() const { return mapped_; }
    // The buffer's device address; only for a buffer made with the address usage.
    std::uint64_t address() const;

    // Both wait for the device; they are meant for setup and the final read-back.
    void upload(const void* data, VkDeviceSize bytes);
    // The first `bytes` bytes, written by `fill` where they are: into the mapped
    // memory itself, or into a staging buffer that is then copied.
    void write(VkDeviceSize bytes, const std::function<void(void*)>& fill);
    void readback(void* data, VkDeviceSize bytes) const;

private:
    void allocate(VkMemoryPropertyFlags wanted, VkMemoryPropertyFlags fallback, bool map);

    const VulkanContext* context_;
    std::string name_;
    VkDeviceSize size_;
    VkBufferUsageFlags usage_;
    // Declared before the buffer, so the buffer is destroyed first.
    DeviceHandle<VkDeviceMemory, vkFreeMemory> memory_;
    DeviceHandle<VkBuffer, vkDestroyBuffer> buffer_;
    void* mapped_ = nullptr;  // persistently mapped while memory_ lives
    bool cached_ = false;
};

}  // namespace vkrt::gpu
