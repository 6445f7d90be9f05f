#include "scene/load_scene.hpp"

#include <fmt/format.h>

#include "scene/gltf_loader.hpp"
#include "scene/json_scene_loader.hpp"
#include "scene/nff_loader.hpp"
#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"

namespace vkrt {

Scene load_scene(const std::filesystem::path& file) {
    const std::string ext = format_extension(file);
    if (ext == ".json" || ext == ".jsonc") {
        return load_json_scene(file);
    }
    if (ext == ".nff") {
        return load_nff_scene(file);
    }
    if (ext == ".gltf" || ext == ".glb") {
        return load_gltf_scene(file);
    }
    throw SceneError(fmt::format(
        "{}: unknown scene format '{}' (expected a .json, .jsonc or .nff scene file, optionally gzipped as .gz, or a .gltf or .glb file)",
        file.string(), ext));
}

}  // namespace vkrt
