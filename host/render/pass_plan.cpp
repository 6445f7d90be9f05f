#include "render/pass_plan.hpp"

#include <algorithm>
#include <cmath>

namespace vkrt {

std::uint32_t next_pass_samples(const PassPlanInput& in) {
    if (in.remaining == 0) return 0;
    if (in.done == 0) return 1;
    double n = double(in.done);
    if (in.seconds_per_sample > 0.0) {
        n = std::min(n, std::max(1.0, std::floor(kPassSeconds / in.seconds_per_sample)));
        if (in.seconds_left) n = std::min(n, std::round(std::max(0.0, *in.seconds_left) / in.seconds_per_sample));
    } else if (in.seconds_left && *in.seconds_left <= 0.0) {
        n = 0.0;  // no measurement to go by, and no time left either
    }
    return static_cast<std::uint32_t>(std::min(n, double(in.remaining)));
}

}  // namespace vkrt
