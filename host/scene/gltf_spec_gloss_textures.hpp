#pragma once
// KHR_materials_pbrSpecularGlossiness's textures as an ordinary metallic-roughness
// material's: the diffuse texture and the specular-glossiness texture converted texel
// by texel (convert_texel, gltf_spec_gloss.hpp) into a base colour texture (8-bit,
// sRGB) and a metallic-roughness texture (8-bit, linear, glTF's packing), so that the
// kernel and the flattening see nothing new (decision 0033).
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "scene/gltf_spec_gloss.hpp"
#include "scene/texture_image.hpp"

namespace tinygltf {
class Value;
struct TextureInfo;
}  // namespace tinygltf

namespace vkrt::gltf {

// One of the extension's textures, decoded with Encoding::SrgbUnlessFloat (its
// colours are sRGB, its alpha linear): its record, whose wrap modes say how it is
// sampled between texels, and the words it is read from (Scene::texels, or an image's
// own words with first_word 0).
struct SourceTexture {
    TextureImage texture;
    std::span<const std::uint32_t> words;
};

struct ConvertedTextures {
    DecodedImage base_color;          // sRGB red, green, blue; alpha the diffuse alpha
    DecodedImage metallic_roughness;  // linear: green roughness, blue metallic (red 0, alpha 1)
};

// The converted textures of a material whose factors are `factors` and diffuse alpha
// `alpha`; an absent texture (null) is taken as 1, so that its factor alone counts.
// The result has the larger width and the larger height of the two (one texture
// alone: its own size), so that neither loses detail: a texture of another size is
// sampled bilinearly at the centre of each result texel, with its own wrap modes, as
// the kernel would sample it there. Values are quantized to the nearest byte: the
// base colour's in sRGB's encoding (nearest_srgb_byte), the rest linearly
// (nearest_byte).
ConvertedTextures convert_textures(const SourceTexture* diffuse, const SourceTexture* specular_glossiness,
                                   const SpecularGlossiness& factors, double alpha);

// The byte b whose b / 255 is nearest to v, clamped to [0, 1]: off by at most 0.5 / 255.
std::uint8_t nearest_byte(double v);

// The byte whose sRGB encoding is nearest to the linear value v's (clamped to
// [0, 1]): its encoded value is off by at most 0.5 / 255, its decoded (linear) one by
// at most that times the decoding's slope, 2.4 / 1.055 at 1, so 0.0045 at most.
std::uint8_t nearest_srgb_byte(double v);

// The textureInfo the extension holds under `key` ("diffuseTexture",
// "specularGlossinessTexture"), or none when absent; a malformed one throws
// SceneError naming `file` and the member under `element`.
std::optional<tinygltf::TextureInfo> read_texture_info(const tinygltf::Value& extension, const char* key,
                                                       const std::string& element, const std::string& file);

}  // namespace vkrt::gltf
