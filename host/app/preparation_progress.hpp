#pragma once
// Progress through the steps before a render's first pass (loading the scene,
// flattening it, setting up the device), for files that take long to prepare: once
// preparation has lasted kShowAfter seconds, the current step and the time so far
// are shown on stderr (rewritten in place on a terminal, a line per step
// otherwise), and nothing at all for the usual file that is ready sooner.
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace vkrt {

class PreparationProgress {
public:
    static constexpr double kShowAfter = 2.0;

    using Clock = std::chrono::steady_clock;

    // `enabled` false: silent (--quiet). With a watcher, a thread shows the step as
    // time passes; without, only poll() does (tests).
    PreparationProgress(bool enabled, std::FILE* out, bool terminal, bool watcher = true);
    ~PreparationProgress();
    PreparationProgress(const PreparationProgress&) = delete;
    PreparationProgress& operator=(const PreparationProgress&) = delete;

    // The step now under way, e.g. "loading model.gltf".
    void step(const std::string& what);
    // Preparation is over: a line rewritten in place is ended.
    void done();
    // Shows what is due at `now`.
    void poll(Clock::time_point now);

private:
    void watch();

    bool enabled_;
    std::FILE* out_;
    bool terminal_;
    Clock::time_point start_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::string step_;
    std::string shown_step_;     // the step last shown (a line per step on a non-terminal)
    Clock::time_point last_draw_;
    bool drawn_ = false;
    bool finished_ = false;
    std::thread watcher_;
};

}  // namespace vkrt
