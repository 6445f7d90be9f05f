#pragma once
// A glTF file's textures (glTF 2.0 specification, 3.8): images held as the bytes of
// their files (PNG, JPEG, ... inside the .glb, in a data URI or beside the file),
// decoded by OpenImageIO when a material uses them, with their samplers' wrap modes
// and KHR_texture_transform.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <tuple>
#include <string>
#include <utility>

#include "scene/scene.hpp"

namespace tinygltf {
class Model;
struct Image;
struct TextureInfo;
}  // namespace tinygltf

namespace vkrt::gltf {

// tinygltf's image loader: keeps the encoded bytes in image->image (vkrt decodes
// them itself, and only those a material uses).
bool keep_image_bytes(tinygltf::Image* image, int index, std::string* error, std::string* warning, int width,
                      int height, const unsigned char* bytes, int size, void* user);

class TextureReader {
public:
    using Note = std::function<void(const std::string&)>;

    TextureReader(const tinygltf::Model& model, std::filesystem::path file, Scene& scene, Note note_unsupported)
        : model_(model), file_(std::move(file)), scene_(scene), note_(std::move(note_unsupported)) {}

    // The scene texture `info` names (decoded once per image, sampler and
    // encoding), its coordinate transform given to `m`: all of a material's
    // textures share one, so a second, different one is named as ignored. None for
    // an absent textureInfo or one vkrt cannot use (said in a warning). `element`
    // is the textureInfo's place, e.g.
    // "materials[0].pbrMetallicRoughness.baseColorTexture".
    std::optional<std::uint32_t> texture(const tinygltf::TextureInfo& info, const std::string& element,
                                         Encoding encoding, Material& m);

private:
    [[noreturn]] void fail_at(const std::string& element, const std::string& what) const;

    const tinygltf::Model& model_;
    std::filesystem::path file_;
    Scene& scene_;
    Note note_;
    std::map<std::tuple<int, int, Encoding>, std::uint32_t> loaded_;  // (image, sampler, encoding) -> scene.textures
};

}  // namespace vkrt::gltf
