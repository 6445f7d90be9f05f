#include "app/preparation_progress.hpp"

#include <fmt/format.h>

namespace vkrt {

PreparationProgress::PreparationProgress(bool enabled, std::FILE* out, bool terminal, bool watcher)
    : enabled_(enabled), out_(out), terminal_(terminal), start_(Clock::now()), last_draw_(start_) {
    if (enabled_ && watcher) watcher_ = std::thread([this] { watch(); });
}

PreparationProgress::~PreparationProgress() { done(); }

void PreparationProgress::step(const std::string& what) {
    std::lock_guard lock(mutex_);
    step_ = what;
}

void PreparationProgress::done() {
    {
        std::lock_guard lock(mutex_);
        if (finished_) return;
        finished_ = true;
        if (enabled_ && terminal_ && drawn_) fmt::print(out_, "\n");
        std::fflush(out_);
    }
    wake_.notify_all();
    if (watcher_.joinable()) watcher_.join();
}

void PreparationProgress::poll(Clock::time_point now) {
    std::lock_guard lock(mutex_);
    if (!enabled_ || finished_) return;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < kShowAfter || step_.empty()) return;
    if (terminal_) {
        if (drawn_ && std::chrono::duration<double>(now - last_draw_).count() < 0.5) return;
        // Trailing spaces wipe the end of a longer line drawn before.
        fmt::print(out_, "\rpreparing: {}, {:.0f} s so far          ", step_, elapsed);
    } else {
        if (step_ == shown_step_) return;
        fmt::print(out_, "preparing: {} ({:.1f} s so far)\n", step_, elapsed);
    }
    std::fflush(out_);
    shown_step_ = step_;
    last_draw_ = now;
    drawn_ = true;
}

void PreparationProgress::watch() {
    std::unique_lock lock(mutex_);
    while (!finished_) {
        wake_.wait_for(lock, std::chrono::milliseconds(250));
        if (finished_) break;
        lock.unlock();
        poll(Clock::now());
        lock.lock();
    }
}

}  // namespace vkrt
