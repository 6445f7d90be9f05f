#pragma once
// What a renderer backend does: take a flattened scene and ranges of sample
// indices, and return per-pixel sums. Vulkan and the C++ reference both implement
// it; nothing above this interface knows which one runs.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "accel/accel_policy.hpp"
#include "kernel/types.hpp"
#include "flatten/flat_scene.hpp"

namespace vkrt {

// Samples [first, first + count) of every pixel. Every random number is a function
// of (seed, pixel, sample index, dimension), so any split of a range traces exactly
// the rays of the whole, and the split sums add up (kernel::add_sums) to the whole's
// bit for bit (tests/render/split_test.cpp).
struct SampleRange {
    std::uint32_t first = 0;
    std::uint32_t count = 1;
    std::uint32_t end() const { return first + count; }
};

// Called now and then from the rendering thread with the work done so far, in
// units of the backend's choosing: done / total is the fraction finished.
using ProgressCallback = std::function<void(std::uint32_t done, std::uint32_t total)>;

struct RenderResult {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<kernel::PixelSum> sums;      // exact radiance sums and sample counts (kernel/sums.glsl)
    std::vector<kernel::Counters> counters;  // lanes: kernel::RAYS_*, kernel::WORK_*
    std::vector<kernel::PassSums> passes;    // with HAS_PASSES, the render passes' sums; else empty
    double setup_seconds = 0.0;        // building pipelines, uploading buffers
    double render_seconds = 0.0;       // the sample loop (GPU timestamps where available)
    double longest_submit_seconds = 0.0;  // Vulkan: the longest single queue submission (wall clock)
    // Vulkan: how the work was laid out on the device (docs/porting.md).
    std::string data_paths;                 // e.g. "scene: texel buffers, params: uniform buffer"
    std::uint32_t slabs = 0;                // pixel buffers' worth of rows rendered one after another
    std::uint32_t tile_width = 0;           // the tiles the pass ended with, in pixels
    std::uint32_t tile_height = 0;
    std::uint32_t device_resets = 0;        // devices lost and recreated during the pass
};

// One scene made ready to render: on Vulkan the pipeline specialised for it and its
// buffers uploaded, which costs far more than a small pass of samples. A
// progressive render keeps one session and renders pass after pass through it.
// The session borrows the FlatScene it was begun with and the Backend that began it:
// both must outlive it.
class RenderSession {
public:
    virtual ~RenderSession() = default;
    // The sums and counters of these samples alone (every pass starts from zero; the
    // caller adds passes up with kernel::add_sums). setup_seconds is 0: see below.
    virtual RenderResult render(SampleRange samples, const ProgressCallback& progress = {}) = 0;
    // What begin() spent setting up, paid once however many passes follow.
    virtual double setup_seconds() const = 0;
};

class Backend {
public:
    virtual ~Backend() = default;
    virtual std::string name() const = 0;         // "vulkan" or "cpu"
    virtual std::string device_name() const = 0;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    virtual std::unique_ptr<RenderSession> begin(const FlatScene& scene) = 0;
    // One range in a session of its own, set-up included in setup_seconds: for
    // callers that render a scene once.
    RenderResult render(const FlatScene& scene, SampleRange samples, const ProgressCallback& progress = {}) {
        const std::unique_ptr<RenderSession> session = begin(scene);
        RenderResult result = session->render(samples, progress);
        result.setup_seconds = session->setup_seconds();
        return result;
    }
    // When this backend prefers brute force to the grid, and its buffer limits.
    virtual AccelPolicy accel_policy() const = 0;
    // Messages the Vulkan validation layer reported so far (0 when it is off).
    virtual std::uint32_t validation_messages() const { return 0; }
};

}  // namespace vkrt
