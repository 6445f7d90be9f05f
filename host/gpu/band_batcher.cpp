#include "gpu/band_batcher.hpp"

#include <algorithm>

namespace vkrt::gpu {

BandBatcher::BandBatcher(std::uint32_t bands, double target_seconds, std::uint32_t max_batch)
    : bands_(std::max(bands, 1u)), target_(target_seconds), max_batch_(std::max(max_batch, 1u)),
      cost_(bands_, -1.0) {}

std::uint32_t BandBatcher::next(std::uint32_t first, std::uint32_t left) const {
    const std::uint32_t most = std::min(left, max_batch_);
    double predicted = 0.0;
    std::uint32_t n = 0;
    while (n < most) {
        const double cost = cost_[(first + n) % bands_];
        if (cost < 0.0) return n == 0 ? 1 : n;
        if (n > 0 && predicted + cost > target_) break;
        predicted += cost;
        ++n;
    }
    return std::max(n, std::min(1u, left));
}

void BandBatcher::measured(std::uint32_t first, std::uint32_t count, double seconds) {
    if (count == 0) return;
    if (count == 1) {
        cost_[first % bands_] = seconds;
        return;
    }
    double predicted = 0.0;
    for (std::uint32_t i = first; i < first + count; ++i) predicted += std::max(cost_[i % bands_], 0.0);
    if (predicted <= 0.0) return;
    const double ratio = seconds / predicted;
    // Each band once, however many samples of it the batch held.
    const std::uint32_t distinct = std::min(count, bands_);
    for (std::uint32_t i = first; i < first + distinct; ++i) cost_[i % bands_] *= ratio;
}

}  // namespace vkrt::gpu
