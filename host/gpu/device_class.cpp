#include "gpu/device_class.hpp"

namespace vkrt::gpu {

namespace {

// Scenes with fewer primitives render faster by brute force than through the grid
// (docs/decisions/0002-grid-threshold.md), from this many spheres deferred sphere
// tests pay (0003): both measured on lavapipe.
constexpr std::uint32_t kBruteForceBelow = 32;
constexpr std::uint32_t kDeferredSpheresFrom = 8;

}  // namespace

DeviceHeuristics heuristics_for(bool cpu_device) {
    DeviceHeuristics h;
    h.accel.brute_force_below = kBruteForceBelow;
    h.accel.deferred_spheres_from = kDeferredSpheresFrom;
    if (cpu_device) {
        h.submit_bound_seconds = 0.25;
        h.measured = true;
        h.name = "cpu";
    } else {
        h.submit_bound_seconds = 0.1;
        h.measured = false;
        h.name = "gpu";
    }
    return h;
}

}  // namespace vkrt::gpu
