#pragma once
// A glTF file's textures (glTF 2.0 specification, 3.8): images held as the bytes of
// their files (PNG, JPEG, ... inside the .glb, in a data URI or beside the file),
// decoded when a material uses them, each once and all in parallel, with their
// samplers' wrap modes and KHR_texture_transform.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "scene/gltf_spec_gloss.hpp"
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

// Materials ask for their textures first (texture, normal_texture,
// specular_glossiness), which checks them and returns tickets; resolve() then decodes
// every image asked for, converts what conversions ask for, and turns the tickets
// into indices of Scene::textures.
class TextureReader {
public:
    using Note = std::function<void(const std::string&)>;

    TextureReader(const tinygltf::Model& model, std::filesystem::path file, Scene& scene, Note note_unsupported)
        : model_(model), file_(std::move(file)), scene_(scene), note_(std::move(note_unsupported)) {}

    // The ticket of the texture `info` names (one per image, sampler and encoding), for
    // the material's slot `slot` (kernel::MAP_<slot>), its mapping of texture
    // coordinates (its TEXCOORD_<n> and KHR_texture_transform) given to `m`: the
    // material's first texture makes the first mapping, a later one on another
    // mapping makes the second (Material::SecondMapping), and one on a third, or a
    // colour texture on another than the first, is left out and named as ignored.
    // None for an absent textureInfo or one vkrt cannot use (said in a warning).
    // `element` is the textureInfo's place, e.g.
    // "materials[0].pbrMetallicRoughness.baseColorTexture".
    std::optional<std::uint32_t> texture(const tinygltf::TextureInfo& info, const std::string& element,
                                         Encoding encoding, std::uint32_t slot, Material& m);

    // The same for a normalTexture: read linear, with its scale.
    std::optional<std::uint32_t> normal_texture(const tinygltf::NormalTextureInfo& info, const std::string& element,
                                                std::uint32_t slot, Material& m);

    // A KHR_materials_pbrSpecularGlossiness material's diffuse and specular-glossiness
    // textures (either may be null), to be converted with its factors and diffuse
    // alpha into a base colour and a metallic-roughness texture
    // (gltf_spec_gloss_textures.hpp): their two tickets, or none when neither texture
    // can be used. Converted texel by texel, both read the first mapping: a texture on
    // another (another transform, other texture coordinates) is left out and counts as
    // absent: its factor alone is converted. The converted textures take the
    // diffuse texture's wrap modes, else the other's; differing ones are named.
    // `element` is the extension object's place.
    struct Converted {
        std::uint32_t base_color = 0;
        std::uint32_t metallic_roughness = 0;
    };
    std::optional<Converted> specular_glossiness(const tinygltf::TextureInfo* diffuse,
                                                 const tinygltf::TextureInfo* specular_glossiness,
                                                 const std::string& element, const SpecularGlossiness& factors,
                                                 double alpha, Material& m);

    // Decodes the images the tickets need, converts what conversions ask for, and
    // returns, for each ticket, its texture's index in Scene::textures.
    std::vector<std::uint32_t> resolve();
    // The texture coordinate sets (TEXCOORD_<n>) of the last material's mappings, when
    // it has textures: the first's, and the second's (-1 without one).
    std::pair<int, int> uv_sets() const { return sets_; }

private:
    [[noreturn]] void fail_at(const std::string& element, const std::string& what) const;
    std::optional<std::uint32_t> request(const tinygltf::TextureInfo& info, const std::string& element,
                                         Encoding encoding, double normal_scale, bool normal, std::uint32_t slot,
                                         Material& m);

    // A texture's mapping of texture coordinates.
    struct Mapping {
        int set = 0;  // TEXCOORD_<set>
        std::array<double, 6> transform;
    };
    // A textureInfo checked, and placed on a mapping of the material's
    // (place_on_mapping; `after_first`: the material has a texture already): its
    // image, sampler and wrap modes, or none when vkrt cannot use it. A texture
    // without a slot of its own (a converted one) must read the first mapping.
    struct Source {
        int image = -1;
        int sampler = -1;
        Wrap wrap_s = Wrap::Repeat;
        Wrap wrap_t = Wrap::Repeat;
    };
    std::optional<Source> source(const tinygltf::TextureInfo& info, const std::string& element,
                                 std::optional<std::uint32_t> slot, bool after_first, Material& m);
    // Puts the texture in `slot` on the material's first mapping, or its second, which
    // this may make; false, and said so, where it fits neither.
    bool place_on_mapping(const Mapping& mapping, std::optional<std::uint32_t> slot, bool after_first, Material& m);
    std::pair<int, int> sets_{0, -1};
    std::size_t encoded_image(int image, Encoding encoding);  // its place in images_, added once

    struct Ticket {
        std::size_t image = 0;  // in images_
        Encoding encoding = Encoding::SrgbUnlessFloat;
        Wrap wrap_s = Wrap::Repeat;
        Wrap wrap_t = Wrap::Repeat;
        double normal_scale = 1.0;
        std::optional<std::size_t> conversion;  // a converted texture instead: conversions_
    };

    // A specular-glossiness material's conversion; its tickets are `ticket` (base
    // colour) and the next (metallic-roughness).
    struct Input {
        std::size_t image;  // in images_
        Wrap wrap_s, wrap_t;
    };
    struct Conversion {
        std::optional<Input> diffuse, specular_glossiness;
        SpecularGlossiness factors;
        double alpha = 1.0;
        std::string element;
        std::uint32_t ticket = 0;
    };
    void convert(const std::vector<TextureImage>& stored, const std::vector<std::size_t>& stored_as_srgb,
                 std::vector<std::uint32_t>& out);

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
    std::vector<Conversion> conversions_;
    // (diffuse image, sampler, specular-glossiness image, sampler, factors and alpha)
    // -> the conversion's first ticket: materials that differ only elsewhere share it.
    std::map<std::tuple<int, int, int, int, std::array<double, 8>>, std::uint32_t> conversion_of_;
};

}  // namespace vkrt::gltf
