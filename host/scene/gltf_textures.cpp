#include "scene/gltf_textures.hpp"

#include <cmath>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "scene/scene_error.hpp"
#include "scene/texture_image.hpp"

namespace vkrt::gltf {

bool keep_image_bytes(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                      int size, void*) {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

namespace {

Wrap wrap_mode(int gl) {
    switch (gl) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::Clamp;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::Mirror;
        default: return Wrap::Repeat;
    }
}

// A file name whose extension tells OpenImageIO the image's format.
std::string format_name(const tinygltf::Image& image) {
    if (image.mimeType == "image/png") return "image.png";
    if (image.mimeType == "image/jpeg") return "image.jpg";
    if (image.mimeType == "image/webp") return "image.webp";
    const std::string ext = std::filesystem::path(image.uri).extension().string();
    return "image" + (ext.empty() ? std::string(".png") : ext);
}

}  // namespace

void TextureReader::fail_at(const std::string& element, const std::string& what) const {
    throw SceneError(fmt::format("{}: {}: {}", file_.string(), element, what));
}

std::optional<std::uint32_t> TextureReader::texture(const tinygltf::TextureInfo& info, const std::string& element,
                                                    Encoding encoding, Material& m) {
    return load(info, element, encoding, std::nullopt, m);
}

std::optional<std::uint32_t> TextureReader::normal_texture(const tinygltf::NormalTextureInfo& info,
                                                           const std::string& element, Material& m) {
    if (!std::isfinite(info.scale) || std::abs(info.scale) > 1e6) {
        fail_at(element + ".scale", fmt::format("expected a number from -1e6 to 1e6, got {}", info.scale));
    }
    tinygltf::TextureInfo plain;
    plain.index = info.index;
    plain.texCoord = info.texCoord;
    plain.extensions = info.extensions;
    return load(plain, element, Encoding::Linear, info.scale, m);
}

std::optional<std::uint32_t> TextureReader::load(const tinygltf::TextureInfo& info, const std::string& element,
                                                 Encoding encoding, std::optional<double> normal_scale, Material& m) {
    if (info.index < 0) return std::nullopt;
    if (static_cast<std::size_t>(info.index) >= model_.textures.size()) {
        fail_at(element + ".index", fmt::format("texture {} does not exist (the file has {})", info.index,
                                                model_.textures.size()));
    }
    const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(info.index)];
    const std::string where = fmt::format("textures[{}]", info.index);
    int tex_coord = info.texCoord;
    std::array<double, 6> transform{1.0, 0.0, 0.0, 0.0, 1.0, 0.0};
    if (auto t = info.extensions.find("KHR_texture_transform"); t != info.extensions.end()) {
        const tinygltf::Value& v = t->second;
        const auto pair = [&](const char* key, double fallback) {
            double out[2] = {fallback, fallback};
            const tinygltf::Value& a = v.Get(key);
            if (a.IsArray() && a.ArrayLen() == 2 && a.Get(0).IsNumber() && a.Get(1).IsNumber()) {
                out[0] = a.Get(0).GetNumberAsDouble();
                out[1] = a.Get(1).GetNumberAsDouble();
            } else if (v.Has(key)) {
                fail_at(element + ".extensions.KHR_texture_transform." + key, "expected an array of 2 numbers");
            }
            return std::pair{out[0], out[1]};
        };
        const auto [ou, ov] = pair("offset", 0.0);
        const auto [su, sv] = pair("scale", 1.0);
        const double rotation = v.Get("rotation").IsNumber() ? v.Get("rotation").GetNumberAsDouble() : 0.0;
        for (double x : {ou, ov, su, sv, rotation}) {
            if (!std::isfinite(x)) fail_at(element + ".extensions.KHR_texture_transform", "a value is not finite");
        }
        transform = texture_transform(ou, ov, rotation, su, sv);
        if (v.Get("texCoord").IsInt()) tex_coord = v.Get("texCoord").GetNumberAsInt();
    }
    if (tex_coord != 0) {
        note_("textures on texture coordinates other than TEXCOORD_0, rendered without the texture");
        return std::nullopt;
    }
    if (m.texture || m.metallic_roughness_texture || m.normal_map || m.emission_texture) {
        if (transform != m.uv_transform) {
            note_("a material's textures with different KHR_texture_transforms, rendered without the later texture");
            return std::nullopt;
        }
    }
    m.uv_transform = transform;
    if (texture.source < 0 || static_cast<std::size_t>(texture.source) >= model_.images.size()) {
        if (texture.source < 0) {
            note_("textures without a source image (or with one of an extension's), rendered without the texture");
            return std::nullopt;
        }
        fail_at(where + ".source", fmt::format("image {} does not exist (the file has {})", texture.source,
                                               model_.images.size()));
    }
    if (texture.sampler >= 0 && static_cast<std::size_t>(texture.sampler) >= model_.samplers.size()) {
        fail_at(where + ".sampler", fmt::format("sampler {} does not exist (the file has {})", texture.sampler,
                                                model_.samplers.size()));
    }
    const auto key = std::tuple{texture.source, texture.sampler, encoding, normal_scale};
    if (auto it = loaded_.find(key); it != loaded_.end()) return it->second;
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(texture.source)];
    const std::string image_element = fmt::format("{}: images[{}]", file_.string(), texture.source);
    if (image.image.empty()) fail_at(fmt::format("images[{}]", texture.source), "the image holds no bytes");
    TextureImage t = load_texture_memory(image.image.data(), image.image.size(), format_name(image), encoding,
                                         image_element);
    if (texture.sampler >= 0) {
        const tinygltf::Sampler& s = model_.samplers[static_cast<std::size_t>(texture.sampler)];
        t.wrap_s = wrap_mode(s.wrapS);
        t.wrap_t = wrap_mode(s.wrapT);
    }
    if (normal_scale) decode_normal_map(t, *normal_scale);
    add_texture(scene_, std::move(t), image_element);
    const auto index = static_cast<std::uint32_t>(scene_.textures.size() - 1);
    loaded_.emplace(key, index);
    return index;
}

}  // namespace vkrt::gltf
