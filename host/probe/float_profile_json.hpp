#pragma once
// `vkrt devices --float-profile --json FILE`: the profile for scripts, one object per
// column. Float results are strings, the shortest text that reads back as the same
// float ("nan", "-inf", "-0" too, which JSON numbers cannot hold); counts and errors
// are numbers, yes-or-no answers booleans.
#include <vector>

#include <nlohmann/json.hpp>

#include "probe/float_profile.hpp"

namespace vkrt::probe {

nlohmann::json float_profile_json(const std::vector<probe::FloatProfile>& columns);

}  // namespace vkrt::probe
