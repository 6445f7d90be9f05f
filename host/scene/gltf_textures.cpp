#include "scene/gltf_textures.hpp"

#include <array>
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
    return request(info, element, encoding, 1.0, false, m);
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
    return request(plain, element, Encoding::Linear, info.scale, true, m);
}

std::optional<std::uint32_t> TextureReader::request(const tinygltf::TextureInfo& info, const std::string& element,
                                                    Encoding encoding, double normal_scale, bool normal, Material& m) {
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
    const auto key = std::tuple{texture.source, texture.sampler, encoding, normal, normal ? normal_scale : 1.0};
    if (auto it = ticket_of_.find(key); it != ticket_of_.end()) return it->second;
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(texture.source)];
    if (image.image.empty()) fail_at(fmt::format("images[{}]", texture.source), "the image holds no bytes");
    auto [at, added] = image_of_.try_emplace(texture.source, images_.size());
    if (added) {
        images_.push_back({image.image.data(), image.image.size(), format_name(image), encoding,
                           fmt::format("{}: images[{}]", file_.string(), texture.source)});
    }
    Ticket ticket;
    ticket.image = at->second;
    ticket.encoding = encoding;
    if (texture.sampler >= 0) {
        const tinygltf::Sampler& s = model_.samplers[static_cast<std::size_t>(texture.sampler)];
        ticket.wrap_s = wrap_mode(s.wrapS);
        ticket.wrap_t = wrap_mode(s.wrapT);
    }
    ticket.normal_scale = normal_scale;
    tickets_.push_back(ticket);
    const auto index = static_cast<std::uint32_t>(tickets_.size() - 1);
    ticket_of_.emplace(key, index);
    return index;
}

std::vector<std::uint32_t> TextureReader::resolve() {
    std::vector<TextureImage> decoded = decode_textures(images_, scene_);
    // An image decoded to half floats in one encoding and wanted in the other as well
    // (a 16-bit PNG as colour and as data) is decoded again in that one.
    std::vector<EncodedImage> again;
    std::map<std::size_t, std::size_t> again_of;  // images_ -> its second decoding in `decoded`
    for (const Ticket& ticket : tickets_) {
        const EncodedImage& image = images_[ticket.image];
        if (ticket.encoding == image.encoding || decoded[ticket.image].format != TexelFormat::Half) continue;
        if (again_of.try_emplace(ticket.image, decoded.size() + again.size()).second) {
            again.push_back(image);
            again.back().encoding = ticket.encoding;
        }
    }
    for (TextureImage& t : decode_textures(again, scene_)) decoded.push_back(std::move(t));
    std::vector<std::uint32_t> out;
    for (const Ticket& ticket : tickets_) {
        const bool other = ticket.encoding != images_[ticket.image].encoding;
        TextureImage t = decoded[other && again_of.count(ticket.image) ? again_of[ticket.image] : ticket.image];
        if (t.format == TexelFormat::Rgba8) t.srgb = ticket.encoding == Encoding::SrgbUnlessFloat;
        t.wrap_s = ticket.wrap_s;
        t.wrap_t = ticket.wrap_t;
        t.normal_scale = ticket.normal_scale;
        out.push_back(add_texture_record(scene_, std::move(t)));
    }
    return out;
}

}  // namespace vkrt::gltf
