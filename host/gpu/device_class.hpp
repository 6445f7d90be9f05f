#pragma once
// The choices that were measured on lavapipe and may well differ elsewhere, per class
// of device. CPU devices (lavapipe) take the measured values; every GPU class takes
// the same values as defaults that no one has measured on it (docs/porting.md says
// how to measure them: `vkrt bench --threshold` for the grid threshold). No Vulkan here.
#include <cstdint>
#include <string>

#include "accel/accel_policy.hpp"

namespace vkrt::gpu {

struct DeviceHeuristics {
    // What one queue submission is planned to take: tiles and batches are sized to
    // stay under it (vulkan_backend.cpp). A CPU device has no watchdog, and lavapipe
    // pays per submission (docs/decisions/0011-loop-budget-and-batched-dispatches.md);
    // a GPU must stay far under its watchdog (2 s on Windows).
    double submit_bound_seconds = 0.0;
    AccelPolicy accel;      // grid threshold, deferred sphere tests
    bool measured = false;  // false: lavapipe's values, unmeasured on this class
    std::string name;       // "cpu", "gpu"
};

DeviceHeuristics heuristics_for(bool cpu_device);

}  // namespace vkrt::gpu
