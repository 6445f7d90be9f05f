#pragma once
// The table of `vkrt devices --float-profile`: one row per property, one column per
// profile (the CPU first), and the Vulkan spec's bound last (docs/numerics.md).
#include <string>
#include <vector>

#include "probe/float_profile.hpp"

namespace vkrt::probe {

std::string float_profile_table(const std::vector<probe::FloatProfile>& columns);

}  // namespace vkrt::probe
