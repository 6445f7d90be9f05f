#pragma once
// Progressive rendering: passes of whole samples (every pixel the same count) through
// one backend session, added exactly into a host-side total, until a sample limit
// or a time budget says stop. The pass sizes come from render/pass_plan.hpp.
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <utility>

#include "render/backend.hpp"

namespace vkrt {

struct ProgressiveLimits {
    SampleRange samples;            // the sample indices to render, at most: first and count
    std::optional<double> seconds;  // stop once this much time is spent on passes
};

// Where a progressive render stands, for a progress display.
struct ProgressiveStatus {
    double samples = 0.0;         // samples per pixel done, counting the current pass's finished part
    std::uint32_t whole_samples = 0;  // of completed passes
    double elapsed = 0.0;         // seconds since the first pass started
    double seconds_left = 0.0;    // estimated, to the sample limit or the time budget, whichever is first
    double fraction() const { return elapsed + seconds_left > 0.0 ? elapsed / (elapsed + seconds_left) : 0.0; }
    double samples_per_second() const { return elapsed > 0.0 ? samples / elapsed : 0.0; }
};
using ProgressiveCallback = std::function<void(const ProgressiveStatus&)>;

class ProgressiveRender {
public:
    // The clock of the time budget starts here: the session's set-up is not part of it.
    ProgressiveRender(RenderSession& session, ProgressiveLimits limits);

    // Renders one more pass, ending at `stop_at` samples per pixel at the latest (a
    // checkpoint of `vkrt converge`); false, rendering nothing, once the limits are
    // reached.
    bool next_pass(std::uint32_t stop_at = std::numeric_limits<std::uint32_t>::max(),
                   const ProgressiveCallback& progress = {});

    // The sums and counters of every pass so far; render_seconds is the backends'
    // sample loops (GPU timestamps on Vulkan), added up.
    const RenderResult& total() const { return total_; }
    // The total, handed over once the passes are done (this one is left empty).
    RenderResult take_total() { return std::exchange(total_, RenderResult{}); }
    std::uint32_t samples_done() const { return done_; }
    std::uint32_t passes() const { return passes_; }
    // Wall-clock seconds of the passes, read-back and accumulation included.
    double seconds() const { return pass_seconds_; }
    // True when the time budget, not the sample limit, ended the render.
    bool stopped_by_time() const { return stopped_by_time_; }
    // Seconds since the first pass started (the time budget's clock).
    double elapsed() const;
    // Estimated from the passes so far: to the sample limit or the time budget,
    // whichever comes first.
    double seconds_left() const;

private:
    RenderSession& session_;
    ProgressiveLimits limits_;
    std::chrono::steady_clock::time_point start_;
    RenderResult total_;
    std::uint32_t done_ = 0;
    std::uint32_t passes_ = 0;
    double pass_seconds_ = 0.0;
    double seconds_per_sample_ = 0.0;
    bool stopped_by_time_ = false;
};

}  // namespace vkrt
