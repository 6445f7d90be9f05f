#pragma once
// Reading a whole input file (scene or mesh) into memory, refusing with a
// SceneError that says why the file could not be read. A gzip-compressed file is
// recognised by its magic bytes, whatever its name, and read decompressed.
#include <filesystem>
#include <string>
#include <string_view>

namespace vkrt {

// The bytes of `file`, decompressed if it is gzip. On failure throws SceneError
// "<name>: cannot open <kind> file (<reason>)", e.g. kind "scene" or "mesh", or
// "<name>: corrupt gzip data (<reason>)".
std::string read_text(const std::filesystem::path& file, const std::string& name, std::string_view kind);

// The file's format extension, looking through a trailing ".gz": ".nff" for
// "balls.nff.gz" as for "balls.nff".
std::string format_extension(const std::filesystem::path& file);

// The file's name without its format extension or ".gz": "balls" for
// "balls.nff.gz" and "balls.nff".
std::string scene_stem(const std::filesystem::path& file);

}  // namespace vkrt
