#pragma once
#include <filesystem>

#include "scene/scene.hpp"

namespace vkrt {

// Loads a scene file, choosing the reader by extension (.json/.jsonc, .nff; other
// classic formats join here). Throws SceneError.
Scene load_scene(const std::filesystem::path& file);

}  // namespace vkrt
