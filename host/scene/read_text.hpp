#pragma once
// Reading a whole input file (scene or mesh) into memory, refusing with a
// SceneError that says why the file could not be read.
#include <filesystem>
#include <string>
#include <string_view>

namespace vkrt {

// The bytes of `file`. On failure throws SceneError
// "<name>: cannot open <kind> file (<reason>)", e.g. kind "scene" or "mesh".
std::string read_text(const std::filesystem::path& file, const std::string& name, std::string_view kind);

}  // namespace vkrt
