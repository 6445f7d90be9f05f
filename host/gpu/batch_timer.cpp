#include "gpu/batch_timer.hpp"

#include <array>
#include <cstdint>

namespace vkrt::gpu {

BatchTimer::BatchTimer(const VulkanContext& context) : context_(context) {
    if (context.timestamp_valid_bits() == 0) {
        return;
    }
    VkQueryPoolCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2;
    VkQueryPool pool = VK_NULL_HANDLE;
    check(vkCreateQueryPool(context.device(), &info, nullptr, &pool), "vkCreateQueryPool");
    pool_ = {context.device(), pool};
}

void BatchTimer::begin(VkCommandBuffer cmd) const {
    if (on_gpu()) {
        vkCmdResetQueryPool(cmd, pool_.get(), 0, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_.get(), 0);
    }
}

void BatchTimer::end(VkCommandBuffer cmd) const {
    if (on_gpu()) {
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 1);
    }
}

double BatchTimer::batch_seconds() const {
    std::array<std::uint64_t, 2> ticks{};
    check(vkGetQueryPoolResults(context_.device(), pool_.get(), 0, 2, sizeof(ticks), ticks.data(),
                                sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    const std::uint32_t bits = context_.timestamp_valid_bits();
    const std::uint64_t mask = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
    const std::uint64_t elapsed = (ticks[1] - ticks[0]) & mask;  // survives one wrap-around
    return double(elapsed) * context_.properties().limits.timestampPeriod * 1e-9;
}

}  // namespace vkrt::gpu
