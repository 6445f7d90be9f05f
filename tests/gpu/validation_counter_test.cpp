// The validation layer's messages are what the Vulkan tests rely on to catch API
// misuse, so the counter behind them must be seen to fire: a deliberately invalid
// call (a zero-sized buffer, which the spec forbids) must raise the count. This test
// reaches into host/gpu/ on purpose; the program itself never includes Vulkan
// outside that folder.
#include <gtest/gtest.h>

#include "gpu/vulkan_context.hpp"

namespace {

TEST(ValidationCounter, CountsAnInvalidCall) {
    vkrt::gpu::VulkanContext context(vkrt::VulkanOptions{"", true});
    EXPECT_EQ(context.validation_messages(), 0u);

    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = 0;  // VUID-VkBufferCreateInfo-size-00912: size must be greater than 0
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    const VkResult result = vkCreateBuffer(context.device(), &info, nullptr, &buffer);
    if (result == VK_SUCCESS && buffer != VK_NULL_HANDLE) vkDestroyBuffer(context.device(), buffer, nullptr);

    EXPECT_GE(context.validation_messages(), 1u);
}

}  // namespace
