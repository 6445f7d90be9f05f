#pragma once
// Adding renders of disjoint sample ranges of one scene: the exact sums of
// kernel/sums.glsl make the total the very result of one render of the union.
#include <algorithm>
#include <stdexcept>
#include <utility>

#include "render/backend.hpp"

namespace vkrt {

// total += part, pixel by pixel; an empty total takes the part's size. Times add
// up too (the longest submission is the longer of the two).
inline void accumulate(RenderResult& total, const RenderResult& part) {
    if (total.sums.empty()) {
        total.width = part.width;
        total.height = part.height;
        total.sums.assign(part.sums.size(), kernel::PixelSum{});
        total.counters.assign(part.counters.size(), kernel::Counters{});
        total.passes.assign(part.passes.size(), kernel::PassSums{});
    }
    if (total.width != part.width || total.height != part.height || total.sums.size() != part.sums.size() ||
        total.counters.size() != part.counters.size() || total.passes.size() != part.passes.size()) {
        throw std::logic_error("accumulate: renders of different sizes");
    }
    for (std::size_t p = 0; p < total.sums.size(); ++p) {
        total.sums[p] = kernel::add_sums(total.sums[p], part.sums[p]);
        total.counters[p] = total.counters[p] + part.counters[p];
    }
    for (std::size_t p = 0; p < total.passes.size(); ++p) {
        total.passes[p] = kernel::add_pass_sums(total.passes[p], part.passes[p]);
    }
    total.setup_seconds += part.setup_seconds;
    total.render_seconds += part.render_seconds;
    total.longest_submit_seconds = std::max(total.longest_submit_seconds, part.longest_submit_seconds);
    total.data_paths = part.data_paths;
    total.slabs = part.slabs;
    total.tile_width = part.tile_width;
    total.tile_height = part.tile_height;
    total.device_resets += part.device_resets;
}

// The same for a part that is no longer needed: the first part becomes the total
// as it is, without zeroing a total and adding to it (a one-pass render's only
// pass, 20 MiB at 513 x 513 corners).
inline void accumulate(RenderResult& total, RenderResult&& part) {
    if (total.sums.empty()) {
        total = std::move(part);
        return;
    }
    accumulate(total, static_cast<const RenderResult&>(part));
}

}  // namespace vkrt
