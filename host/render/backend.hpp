#pragma once
// What a renderer backend does: take a flattened scene and a range of sample
// indices, and return per-pixel sums. Vulkan and the C++ reference both implement
// it; nothing above this interface knows which one runs.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "accel/accel_policy.hpp"
#include "kernel_types.hpp"
#include "scene/scene_gpu.hpp"

namespace vkrt {

// Samples [first, first + count) of every pixel. Every random number is a function
// of (seed, pixel, sample index, dimension), so any split of a range traces exactly
// the rays of the whole; adding the split sums equals the whole's sums up to the
// float rounding of that last addition (tests/split_test.cpp).
struct SampleRange {
    std::uint32_t first = 0;
    std::uint32_t count = 1;
};

// Called now and then from the rendering thread with the work done so far, in
// units of the backend's choosing: done / total is the fraction finished.
using ProgressCallback = std::function<void(std::uint32_t done, std::uint32_t total)>;

struct RenderResult {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<kernel::PixelSum> sums;      // exact radiance sums and sample counts (kernel/sums.glsl)
    std::vector<kernel::Counters> counters;  // lanes: kernel::RAYS_*, kernel::WORK_*
    double setup_seconds = 0.0;        // building pipelines, uploading buffers
    double render_seconds = 0.0;       // the sample loop (GPU timestamps where available)
};

class Backend {
public:
    virtual ~Backend() = default;
    virtual std::string name() const = 0;         // "vulkan" or "cpu"
    virtual std::string device_name() const = 0;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    virtual RenderResult render(const SceneGpu& scene, SampleRange samples,
                                const ProgressCallback& progress = {}) = 0;
    // When this backend prefers brute force to the grid, and its buffer limits.
    virtual AccelPolicy accel_policy() const = 0;
    // Messages the Vulkan validation layer reported so far (0 when it is off).
    virtual std::uint32_t validation_messages() const { return 0; }
};

}  // namespace vkrt
