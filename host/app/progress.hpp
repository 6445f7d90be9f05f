#pragma once
// Progress for renders long enough to wonder about (over a second): a line rewritten
// in place on a terminal, a plain line every tenth of the work otherwise, nothing
// when quiet.
#include <chrono>
#include <string>

namespace vkrt {

class ProgressReporter {
public:
    ProgressReporter(std::string label, bool enabled);
    // `fraction` of the work is done and `seconds_left` estimated; `detail` (e.g.
    // "12 spp, 3.4 spp/s") is shown beside the bar.
    void update(double fraction, double seconds_left, const std::string& detail);
    void finish();

private:
    std::string label_;
    bool enabled_;
    bool terminal_;
    bool shown_ = false;
    int last_decile_ = -1;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace vkrt
