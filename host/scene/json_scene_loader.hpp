#pragma once
#include <filesystem>
#include <string>

#include "scene/scene.hpp"

namespace vkrt {

// Reads a JSON scene file (comments allowed) and validates every field.
// Throws SceneError naming the file and the JSON path (e.g. "objects[3].radius").
Scene load_json_scene(const std::filesystem::path& file);

// The same for scene text already in memory; `source` names it in messages and
// anchors its relative paths (meshes), as the file's own path would.
Scene parse_json_scene(const std::string& text, const std::filesystem::path& source);

}  // namespace vkrt
