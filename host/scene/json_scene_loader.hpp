#pragma once
#include <filesystem>

#include "scene/scene.hpp"

namespace vkrt {

// Reads a JSON scene file (comments allowed) and validates every field.
// Throws SceneError naming the file and the JSON path (e.g. "objects[3].radius").
Scene load_json_scene(const std::filesystem::path& file);

}  // namespace vkrt
