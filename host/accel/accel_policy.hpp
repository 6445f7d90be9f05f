#pragma once
// What a backend tells the scene builder about acceleration: below how many
// primitives brute force beats the grid on it (measured with `vkrt bench
// --threshold`, docs/grid.md), and how many entries one grid array may hold.
#include <cstdint>

namespace vkrt {

struct AccelPolicy {
    std::uint32_t brute_force_below = 0;       // "auto" uses the grid from this many primitives on
    std::uint64_t max_buffer_entries = 0xFFFFFFFFu;
    // Without the grid, brute force tests the spheres a ray starts near after its
    // loop over them (DEFERRED_SPHERES) from this many spheres on; below it the extra
    // loops cost more than they save (docs/decisions/0003-deferred-sphere-tests.md).
    std::uint32_t deferred_spheres_from = 8;
};

}  // namespace vkrt
