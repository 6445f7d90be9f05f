#pragma once
#include <nlohmann/json.hpp>

#include "render/render.hpp"

namespace vkrt {

// The --stats report; its fields are documented in docs/cli.md.
nlohmann::json stats_to_json(const RenderStats& stats);

}  // namespace vkrt
