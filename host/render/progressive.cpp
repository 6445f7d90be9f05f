#include "render/progressive.hpp"

#include <algorithm>

#include "render/accumulate.hpp"
#include "render/pass_plan.hpp"

namespace vkrt {

ProgressiveRender::ProgressiveRender(RenderSession& session, ProgressiveLimits limits)
    : session_(session), limits_(limits), start_(std::chrono::steady_clock::now()) {}

double ProgressiveRender::elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double ProgressiveRender::seconds_left() const {
    const std::uint32_t remaining = limits_.samples.count - done_;
    double left = done_ > 0 && pass_seconds_ > 0.0 ? remaining * (pass_seconds_ / done_) : 0.0;
    if (limits_.seconds) left = std::min(left, std::max(0.0, *limits_.seconds - elapsed()));
    return left;
}

bool ProgressiveRender::next_pass(std::uint32_t stop_at, const ProgressiveCallback& progress) {
    const std::uint32_t limit = std::min(limits_.samples.count, stop_at);
    PassPlanInput plan;
    plan.done = done_;
    plan.remaining = limit > done_ ? limit - done_ : 0;
    plan.seconds_per_sample = seconds_per_sample_;
    if (limits_.seconds) plan.seconds_left = *limits_.seconds - elapsed();
    const std::uint32_t count = next_pass_samples(plan);
    if (count == 0) {
        stopped_by_time_ = plan.remaining > 0;
        return false;
    }

    const auto pass_start = std::chrono::steady_clock::now();
    ProgressCallback pass_progress;
    if (progress) {
        pass_progress = [&](std::uint32_t part, std::uint32_t parts) {
            ProgressiveStatus s;
            s.whole_samples = done_ + (part == parts ? count : 0);
            s.samples = done_ + double(count) * part / std::max(parts, 1u);
            s.elapsed = elapsed();
            const double rate = s.samples_per_second();
            s.seconds_left = rate > 0.0 ? (limits_.samples.count - s.samples) / rate : 0.0;
            if (limits_.seconds) s.seconds_left = std::min(s.seconds_left, std::max(0.0, *limits_.seconds - s.elapsed));
            progress(s);
        };
    }
    accumulate(total_, session_.render(SampleRange{limits_.samples.first + done_, count}, pass_progress));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_start).count();
    pass_seconds_ += seconds;
    seconds_per_sample_ = seconds / count;
    done_ += count;
    ++passes_;
    return true;
}

}  // namespace vkrt
