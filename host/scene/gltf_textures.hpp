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
struct NormalTextureInfo;
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

    // The same for a normalTexture: read linear and decoded with its scale
    // (decode_normal_map, texture_image.hpp).
    std::optional<std::uint32_t> normal_texture(const tinygltf::NormalTextureInfo& info, const std::string& element,
                                                Material& m);

private:
    [[noreturn]] void fail_at(const std::string& element, const std::string& what) const;
    std::optional<std::uint32_t> load(const tinygltf::TextureInfo& info, const std::string& element, Encoding encoding,
                                      std::optional<double> normal_scale, Material& m);

    const tinygltf::Model& model_;
    std::filesystem::path file_;
    Scene& scene_;
    Note note_;
    // (image, sampler, encoding, a normal map's scale) -> scene.textures
    std::map<std::tuple<int, int, Encoding, std::optional<double>>, std::uint32_t> loaded_;
};

}  // namespace vkrt::gltf
