#include "app/progress.hpp"

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>
#include <unistd.h>

namespace vkrt {

ProgressReporter::ProgressReporter(std::string label, bool enabled)
    : label_(std::move(label)),
      enabled_(enabled),
      terminal_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void ProgressReporter::update(double fraction, double seconds_left, const std::string& detail) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0) return;
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (terminal_) {
        if (std::chrono::duration<double>(now - last_draw_).count() < 0.1 && fraction < 1.0) return;
        last_draw_ = now;
        constexpr int kWidth = 30;
        const int filled = int(fraction * kWidth);
        // Trailing spaces wipe the end of a longer line drawn before.
        fmt::print(stderr, "\r{} [{}{}] {:3.0f}%  {}, {:.1f} s left   ", label_, std::string(filled, '#'),
                   std::string(kWidth - filled, '.'), fraction * 100.0, detail, seconds_left);
        std::fflush(stderr);
        shown_ = true;
    } else {
        const int decile = int(fraction * 10.0);
        // Estimates of the time left move, so the fraction can step back: never repeat a decile.
        if (decile <= last_decile_) return;
        last_decile_ = decile;
        fmt::print(stderr, "{}: {:.0f}% ({}, {:.1f} s elapsed, {:.1f} s left)\n", label_, fraction * 100.0, detail,
                   elapsed, seconds_left);
    }
}

void ProgressReporter::finish() {
    if (shown_) {
        fmt::print(stderr, "\n");
        shown_ = false;
    }
}

}  // namespace vkrt
