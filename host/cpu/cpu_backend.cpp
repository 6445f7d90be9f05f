#include "cpu/cpu_backend.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "kernel/kernel.hpp"

namespace vkrt {
namespace {

// Tiles keep each thread on a compact patch of pixels (cache-friendly scene access
// pattern, like a workgroup) and balance load across threads by work stealing from
// one atomic counter.
constexpr std::uint32_t kTileSize = 16;

// Scenes with fewer primitives render faster by brute force than through the grid on
// this backend (docs/decisions/0002-grid-threshold.md; `vkrt bench --threshold`).
constexpr std::uint32_t kBruteForceBelow = 32;

}  // namespace

kernel::Kernel make_kernel(const FlatScene& scene) {
    kernel::Kernel k;
#define FEATURE(id, name) k.name = scene.features.has(std::uint32_t(id));
#include "kernel/features.glsl"
#undef FEATURE
    k.params = scene.params;
#define SCENE_ARRAY(id, name, Element, load, format) k.name = scene.name;
#include "kernel/arrays.glsl"
    return k;
}

namespace {

// The reference has nothing to set up: a session only remembers the scene and the
// thread count, and each pass starts its threads afresh.
class ReferenceSession final : public RenderSession {
public:
    ReferenceSession(const FlatScene& scene, unsigned threads) : scene_(scene), threads_(threads) {}

    double setup_seconds() const override { return 0.0; }

    RenderResult render(SampleRange samples, const ProgressCallback& progress) override {
        RenderResult out;
        out.width = scene_.width();
        out.height = scene_.height();
        out.sums.assign(scene_.pixel_count(), kernel::PixelSum{});
        out.counters.assign(scene_.pixel_count(), kernel::Counters{});
        const bool passes = scene_.features.has(Feature::HAS_PASSES);
        if (passes) out.passes.assign(scene_.pixel_count(), kernel::PassSums{});
        // The clock starts after the output arrays exist, as the Vulkan backend's
        // timestamps start after its sums are cleared: render_seconds is the sample
        // loop (and starting the threads that run it). Fresh arrays fault their
        // pages in as they are zeroed, 160 bytes a pixel, which timed here made the
        // reference look up to 2x slower whenever the allocator handed out fresh
        // pages (docs/bench.md has the measurement).
        const auto start = std::chrono::steady_clock::now();

        const std::uint32_t tiles_x = (out.width + kTileSize - 1) / kTileSize;
        const std::uint32_t tiles_y = (out.height + kTileSize - 1) / kTileSize;
        const std::uint32_t tile_count = tiles_x * tiles_y;
        std::atomic<std::uint32_t> next_tile{0};
        std::atomic<std::uint32_t> tiles_done{0};
        std::mutex progress_mutex;

        auto worker = [&] {
            kernel::Kernel k = make_kernel(scene_);
            for (std::uint32_t tile = next_tile++; tile < tile_count; tile = next_tile++) {
                const std::uint32_t x0 = (tile % tiles_x) * kTileSize;
                const std::uint32_t y0 = (tile / tiles_x) * kTileSize;
                const std::uint32_t x1 = std::min(x0 + kTileSize, out.width);
                const std::uint32_t y1 = std::min(y0 + kTileSize, out.height);
                for (std::uint32_t y = y0; y < y1; ++y) {
                    for (std::uint32_t x = x0; x < x1; ++x) {
                        const std::size_t index = std::size_t(y) * out.width + x;
                        for (std::uint32_t s = samples.first; s < samples.end(); ++s) {
                            const auto result = k.render_sample(x, y, s);
                            k.accumulate_sample(result, out.sums[index], out.counters[index]);
                            if (passes) k.accumulate_passes(result, out.passes[index]);
                        }
                    }
                }
                const std::uint32_t done = ++tiles_done;
                if (progress) {
                    std::lock_guard lock(progress_mutex);
                    progress(done, tile_count);
                }
            }
        };

        const unsigned n = std::min<unsigned>(threads_, std::max(1u, tile_count));
        std::vector<std::jthread> pool;
        for (unsigned i = 1; i < n; ++i) pool.emplace_back(worker);
        worker();
        pool.clear();  // joins

        out.render_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return out;
    }

private:
    const FlatScene& scene_;
    unsigned threads_;
};

class ReferenceBackend final : public Backend {
public:
    explicit ReferenceBackend(unsigned threads)
        : threads_(threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency())) {}

    std::string name() const override { return "cpu"; }
    AccelPolicy accel_policy() const override { return {kBruteForceBelow, 0xFFFFFFFFu}; }
    std::string device_name() const override {
        return "C++ reference, " + std::to_string(threads_) + " thread" + (threads_ == 1 ? "" : "s");
    }
    std::unique_ptr<RenderSession> begin(const FlatScene& scene) override {
        return std::make_unique<ReferenceSession>(scene, threads_);
    }

private:
    unsigned threads_;
};

}  // namespace

std::unique_ptr<Backend> make_cpu_backend(unsigned threads) {
    return std::make_unique<ReferenceBackend>(threads);
}

}  // namespace vkrt
