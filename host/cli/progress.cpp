#include "cli/progress.hpp"

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

void ProgressReporter::update(std::uint32_t done, std::uint32_t total) {
    if (!enabled_ || total == 0) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0) return;
    const double fraction = double(done) / double(total);
    const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    if (terminal_) {
        if (std::chrono::duration<double>(now - last_draw_).count() < 0.1 && done != total) return;
        last_draw_ = now;
        constexpr int kWidth = 30;
        const int filled = int(fraction * kWidth);
        fmt::print(stderr, "\r{} [{}{}] {:3.0f}%  {:.1f} s left ", label_, std::string(filled, '#'),
                   std::string(kWidth - filled, '.'), fraction * 100.0, left);
        std::fflush(stderr);
        shown_ = true;
    } else {
        const int decile = int(fraction * 10.0);
        if (decile == last_decile_) return;
        last_decile_ = decile;
        fmt::print(stderr, "{}: {:.0f}% ({:.1f} s elapsed, {:.1f} s left)\n", label_, fraction * 100.0, elapsed, left);
    }
}

void ProgressReporter::finish() {
    if (shown_) {
        fmt::print(stderr, "\n");
        shown_ = false;
    }
}

}  // namespace vkrt
