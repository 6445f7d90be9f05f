#pragma once
// How many samples the next pass of a progressive render takes (render/progressive.hpp).
#include <cstdint>
#include <optional>

namespace vkrt {

// A pass should stay around a second: long enough that the per-pass costs (a
// read-back and an exact addition of every pixel's sums) stay small, short enough
// that a time budget is overshot by little and the image can be looked at often.
inline constexpr double kPassSeconds = 1.0;

struct PassPlanInput {
    std::uint32_t done = 0;        // samples per pixel rendered so far
    std::uint32_t remaining = 0;   // samples left before the sample limit or the next checkpoint
    double seconds_per_sample = 0; // measured on the last pass; 0 before the first
    std::optional<double> seconds_left;  // of a time budget, when there is one
};

// The samples of the next pass, 0 when the render should stop. The first pass is one
// sample (always, so that even a tiny budget gives an image); then each pass renders
// as many as are done (1, 1, 2, 4, ...: the counts done are powers of two, the
// checkpoints of `vkrt converge`), at most what fits in kPassSeconds. Under a time
// budget, a pass takes the samples that fit in the time left, rounded to the
// nearest: the budget is overshot by at most half a sample's time plus the
// misestimate, and undershot by at most as much.
std::uint32_t next_pass_samples(const PassPlanInput& in);

}  // namespace vkrt
