#pragma once
// How many dispatches one Vulkan queue submission takes. The work is a sequence of
// items, sample by sample and within a sample band by band (item i is band
// i % bands). Bands cost very different amounts (a band of sky against one of a
// sphereflake), so a submission is planned from what each band was measured to
// cost, never from an average: a batch of cheap bands must not grow into one that
// runs into the expensive ones. No Vulkan here, so the tests can drive it.
#include <cstdint>
#include <vector>

namespace vkrt::gpu {

class BandBatcher {
public:
    BandBatcher(std::uint32_t bands, double target_seconds, std::uint32_t max_batch);

    // The items, from `first` on, that the next submission takes: as many as the
    // measured costs fit in the target, at least one, at most `left` and the
    // maximum. A band not measured yet goes alone, so that it gets measured.
    std::uint32_t next(std::uint32_t first, std::uint32_t left) const;

    // The submission of items [first, first + count) took `seconds`: a lone band
    // gets its cost; a batch rescales the costs of its bands by measured / predicted,
    // which follows a machine that speeds up or slows down.
    void measured(std::uint32_t first, std::uint32_t count, double seconds);

private:
    std::uint32_t bands_;
    double target_;
    std::uint32_t max_batch_;
    std::vector<double> cost_;  // seconds of one band of one sample; < 0 while unknown
};

}  // namespace vkrt::gpu
