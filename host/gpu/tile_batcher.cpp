#include "gpu/tile_batcher.hpp"

#include <algorithm>

#include "gpu/render_interface.hpp"

namespace vkrt::gpu {

namespace {

std::uint32_t round_up(std::uint32_t value) { return (value + kWorkgroupSide - 1) / kWorkgroupSide * kWorkgroupSide; }

}  // namespace

bool Tiling::split() {
    if (tile_width <= kWorkgroupSide && tile_height <= kWorkgroupSide) return false;
    if (tile_width >= tile_height) {
        tile_width = round_up(tile_width / 2);
    } else {
        tile_height = round_up(tile_height / 2);
    }
    return true;
}

Tiling tile_slab(std::uint32_t width, std::uint32_t rows, std::uint32_t tile_width, std::uint32_t tile_height) {
    Tiling t;
    t.width = width;
    t.rows = rows;
    t.tile_width = std::max(kWorkgroupSide, round_up(std::min(tile_width, width)));
    t.tile_height = std::max(kWorkgroupSide, round_up(std::min(tile_height, rows)));
    return t;
}

std::vector<Region> rest_of_sample(const Region& region, const Tiling& tiling, std::uint32_t next_tile) {
    if (next_tile == 0) return {region};
    std::vector<Region> rest;
    if (next_tile >= tiling.count()) return rest;
    const std::uint32_t column = next_tile % tiling.across() * tiling.tile_width;
    const std::uint32_t row = next_tile / tiling.across() * tiling.tile_height;
    if (column == 0) return {{region.x, region.y + row, region.width, region.rows - row}};
    const std::uint32_t below = std::min(row + tiling.tile_height, region.rows);
    rest.push_back({region.x + column, region.y + row, region.width - column, below - row});
    if (below < region.rows) rest.push_back({region.x, region.y + below, region.width, region.rows - below});
    return rest;
}

TileBatcher::TileBatcher(std::uint32_t tiles, double target_seconds, std::uint32_t max_batch)
    : tiles_(std::max(tiles, 1u)), target_(target_seconds), max_batch_(std::max(max_batch, 1u)),
      cost_(tiles_, -1.0) {}

std::uint32_t TileBatcher::next(std::uint32_t first, std::uint32_t left) const {
    const std::uint32_t most = std::min(left, max_batch_);
    double predicted = 0.0;
    std::uint32_t n = 0;
    while (n < most) {
        const double cost = cost_[(first + n) % tiles_];
        if (cost < 0.0) return n == 0 ? 1 : n;
        if (n > 0 && predicted + cost > target_) break;
        predicted += cost;
        ++n;
    }
    return std::max(n, std::min(1u, left));
}

void TileBatcher::measured(std::uint32_t first, std::uint32_t count, double seconds) {
    if (count == 0) return;
    if (count == 1) {
        cost_[first % tiles_] = seconds;
        return;
    }
    double predicted = 0.0;
    for (std::uint32_t i = first; i < first + count; ++i) predicted += std::max(cost_[i % tiles_], 0.0);
    if (predicted <= 0.0) return;
    const double ratio = seconds / predicted;
    // Each tile once, however many samples of it the batch held.
    const std::uint32_t distinct = std::min(count, tiles_);
    for (std::uint32_t i = first; i < first + distinct; ++i) cost_[i % tiles_] *= ratio;
}

double TileBatcher::costliest() const {
    double most = 0.0;
    for (const double cost : cost_) most = std::max(most, cost);
    return most;
}

}  // namespace vkrt::gpu
