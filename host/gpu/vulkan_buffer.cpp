#include "gpu/vulkan_buffer.hpp"

#include <cstring>
#include <utility>

namespace vkrt::gpu {

namespace {

constexpr VkMemoryPropertyFlags kMappedDevice = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT |
                                                VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
constexpr VkMemoryPropertyFlags kHostCoherent =
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

// The first allowed memory type having all of `flags`, or UINT32_MAX.
std::uint32_t find_memory_type(const VkPhysicalDeviceMemoryProperties& memory,
                               std::uint32_t allowed, VkMemoryPropertyFlags flags) {
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if ((allowed & (1u << i)) != 0 && (memory.memoryTypes[i].propertyFlags & flags) == flags) {
            return i;
        }
    }
    return UINT32_MAX;
}

}  // namespace

VulkanBuffer::VulkanBuffer(const VulkanContext& context, std::string name, VkDeviceSize size,
                           VkBufferUsageFlags usage, Placement placement)
    : context_(&context), name_(std::move(name)), size_(size), usage_(usage) {
    if (size == 0) {
        throw GpuError("buffer '" + name_ + "' would be empty");
    }
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    // Transfer usage always: fills, staging copies and read-back all need it.
    info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(context.device(), &info, nullptr, &buffer), "vkCreateBuffer");
    buffer_ = DeviceHandle<VkBuffer, vkDestroyBuffer>(context.device(), buffer);

    if (placement == Placement::Staging) {
        allocate(kHostCoherent, kHostCoherent, true);
    } else if (placement == Placement::Readback) {
        allocate(kHostCoherent | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, kHostCoherent, true);
    } else if (!context.limits().mapped_device_memory) {
        allocate(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, false);
    } else {
        allocate(kMappedDevice, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, true);
    }
}

// Tries `wanted`; if no memory type has it, or its heap is full (a GPU's small
// mappable window), falls back to `fallback`. Maps the memory when `map` allows and
// the type is host-coherent.
void VulkanBuffer::allocate(VkMemoryPropertyFlags wanted, VkMemoryPropertyFlags fallback, bool map) {
    const VkDevice device = context_->device();
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(device, buffer_.get(), &req);
    const VkPhysicalDeviceMemoryProperties& memory = context_->memory_properties();

    VkMemoryAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    info.allocationSize = req.size;
    VkMemoryAllocateFlagsInfo address_flags{};
    address_flags.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO;
    address_flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    if (usage_ & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) {
        info.pNext = &address_flags;
    }
    VkDeviceMemory raw = VK_NULL_HANDLE;
    auto try_flags = [&](VkMemoryPropertyFlags flags) {
        info.memoryTypeIndex = find_memory_type(memory, req.memoryTypeBits, flags);
        if (info.memoryTypeIndex == UINT32_MAX) {
            return VK_ERROR_FEATURE_NOT_PRESENT;
        }
        return vkAllocateMemory(device, &info, nullptr, &raw);
    };
    VkResult result = try_flags(wanted);
    if ((result == VK_ERROR_FEATURE_NOT_PRESENT || result == VK_ERROR_OUT_OF_DEVICE_MEMORY) &&
        fallback != wanted) {
        result = try_flags(fallback);
    }
    if (result == VK_ERROR_FEATURE_NOT_PRESENT) {
        throw GpuError("buffer '" + name_ + "': the device has no suitable memory type");
    }
    if (result != VK_SUCCESS) {
        throw GpuError("vkAllocateMemory failed for buffer '" + name_ + "' (" +
                       std::to_string(req.size) + " bytes): " + result_name(result));
    }
    memory_ = DeviceHandle<VkDeviceMemory, vkFreeMemory>(device, raw);
    check(vkBindBufferMemory(device, buffer_.get(), raw, 0), "vkBindBufferMemory");

    const VkMemoryPropertyFlags flags = memory.memoryTypes[info.memoryTypeIndex].propertyFlags;
    if (map && (flags & kHostCoherent) == kHostCoherent) {
        check(vkMapMemory(device, raw, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
        cached_ = (flags & VK_MEMORY_PROPERTY_HOST_CACHED_BIT) != 0;
    }
}

std::uint64_t VulkanBuffer::address() const {
    if ((usage_ & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) == 0) {
        throw GpuError("buffer '" + name_ + "' was not made for device addresses");
    }
    VkBufferDeviceAddressInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO;
    info.buffer = buffer_.get();
    return vkGetBufferDeviceAddress(context_->device(), &info);
}

void VulkanBuffer::upload(const void* data, VkDeviceSize bytes) {
    write(bytes, [&](void* out) { std::memcpy(out, data, bytes); });
}

void VulkanBuffer::write(VkDeviceSize bytes, const std::function<void(void*)>& fill) {
    if (bytes > size_) {
        throw GpuError("upload of " + std::to_string(bytes) + " bytes into buffer '" + name_ +
                       "' of " + std::to_string(size_));
    }
    if (mapped_) {
        // Coherent memory: vkQueueSubmit makes host writes visible to later commands.
        fill(mapped_);
        return;
    }
    VulkanBuffer staging(*context_, name_ + " (staging)", bytes, 0, Placement::Staging);
    staging.write(bytes, fill);
    context_->submit_and_wait([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging.get(), buffer_.get(), 1, &region);
        // Everything later on this queue, whichever stage, sees the copy.
        memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    });
}

void VulkanBuffer::readback(void* data, VkDeviceSize bytes) const {
    if (bytes > size_) {
        throw GpuError("read-back of " + std::to_string(bytes) + " bytes from buffer '" + name_ +
                       "' of " + std::to_string(size_));
    }
    if (mapped_) {
        // Device writes reach the host only through a barrier to the host stage.
        context_->submit_and_wait([&](VkCommandBuffer cmd) {
            memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                           VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        });
        std::memcpy(data, mapped_, bytes);
        return;
    }
    VulkanBuffer staging(*context_, name_ + " (staging)", bytes, 0, Placement::Staging);
    context_->submit_and_wait([&](VkCommandBuffer cmd) {
        memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, buffer_.get(), staging.get(), 1, &region);
        memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    std::memcpy(data, staging.mapped_, bytes);
}

}  // namespace vkrt::gpu
