#pragma once
// A glTF file's textures (glTF 2.0 specification, 3.8): images held as the bytes of
// their files (PNG, JPEG, ... inside the .glb, in a data URI or beside the file),
// decoded when a material uses them, each once and all in parallel, with their
// samplers' wrap modes and KHR_texture_transform.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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

// Materials ask for their textures first (texture, normal_texture), which checks
// them and returns a ticket; resolve() then decodes every image asked for and turns
// the tickets into indices of Scene::textures.
class TextureReader {
public:
    using Note = std::function<void(const std::string&)>;

    TextureReader(const tinygltf::Model& model, std::filesystem::path file, Scene& scene, Note note_unsupported)
        : model_(model), file_(std::move(file)), scene_(scene), note_(std::move(note_unsupported)) {}

    // The ticket of the texture `info` names (one per image, sampler and encoding),
    // its coordinate transform given to `m`: all of a material's textures share one,
    // so a second, different one is named as ignored. None for an absent textureInfo
    // or one vkrt cannot use (said in a warning). `element` is the textureInfo's
    // place, e.g. "materials[0].pbrMetallicRoughness.baseColorTexture".
    std::optional<std::uint32_t> texture(const tinygltf::TextureInfo& info, const std::string& element,
                                         Encoding encoding, Material& m);

    // The same for a normalTexture: read linear, with its scale.
    std::optional<std::uint32_t> normal_texture(const tinygltf::NormalTextureInfo& info, const std::string& element,
                                                Material& m);

    // Decodes the images the tickets need and returns, for each ticket, its texture's
    // index in Scene::textures.
    std::vector<std::uint32_t> resolve();

private:
    [[noreturn]] void fail_at(const std::string& element, const std::string& what) const;
    std::optional<std::uint32_t> request(const tinygltf::TextureInfo& info, const std::string& element,
                                         Encoding encoding, double normal_scale, bool normal, Material& m);

    struct Ticket {
        std::size_t image;  // in images_
        Encoding encoding = Encoding::SrgbUnlessFloat;
        Wrap wrap_s = Wrap::Repeat;
        Wrap wrap_t = Wrap::Repeat;
        double normal_scale = 1.0;
    };

    const tinygltf::Model& model_;
    std::filesystem::path file_;
    Scene& scene_;
    Note note_;
    // To decode, each once: an 8-bit image serves as colour and as data alike (the
    // kernel decodes sRGB), so images are told apart by their encoding only when they
    // decode to half floats (decode_textures: 16-bit and float files).
    std::vector<EncodedImage> images_;
    std::map<int, std::size_t> image_of_;  // glTF image -> images_
    std::vector<Ticket> tickets_;
    // (image, sampler, encoding, normal map, its scale) -> tickets_
    std::map<std::tuple<int, int, Encoding, bool, double>, std::uint32_t> ticket_of_;
};

}  // namespace vkrt::gltf
