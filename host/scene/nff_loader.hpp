#pragma once
#include <filesystem>

#include "scene/scene.hpp"

namespace vkrt {

// Reads a scene in Eric Haines' Neutral File Format, the format of the Standard
// Procedural Databases (docs/nff.md), and validates every line. Throws SceneError
// naming the file and line ("balls.nff:12: ...").
Scene load_nff_scene(const std::filesystem::path& file);

}  // namespace vkrt
