#pragma once
// The whole-render timer: GPU timestamps around each batch where the queue has them.
#include "gpu/vulkan_context.hpp"

namespace vkrt::gpu {

class BatchTimer {
public:
    explicit BatchTimer(const VulkanContext& context);
    // False where the queue has no timestamps; then nothing is recorded and the
    // caller times on the host.
    bool on_gpu() const { return pool_.get() != VK_NULL_HANDLE; }

    void begin(VkCommandBuffer cmd) const;
    void end(VkCommandBuffer cmd) const;
    // After the batch's fence: its GPU time, in seconds.
    double batch_seconds() const;

private:
    const VulkanContext& context_;
    DeviceHandle<VkQueryPool, vkDestroyQueryPool> pool_;
};

}  // namespace vkrt::gpu
