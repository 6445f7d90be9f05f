#include "scene/gltf_textures.hpp"

#include <array>
#include <cmath>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "scene/gltf_spec_gloss_textures.hpp"
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
                                                    Encoding encoding, std::uint32_t slot, Material& m) {
    return request(info, element, encoding, 1.0, false, slot, m);
}

std::optional<std::uint32_t> TextureReader::normal_texture(const tinygltf::NormalTextureInfo& info,
                                                           const std::string& element, std::uint32_t slot, Material& m) {
    if (!std::isfinite(info.scale) || std::abs(info.scale) > 1e6) {
        fail_at(element + ".scale", fmt::format("expected a number from -1e6 to 1e6, got {}", info.scale));
    }
    tinygltf::TextureInfo plain;
    plain.index = info.index;
    plain.texCoord = info.texCoord;
    plain.extensions = info.extensions;
    return request(plain, element, Encoding::Linear, info.scale, true, slot, m);
}

std::optional<TextureReader::Source> TextureReader::source(const tinygltf::TextureInfo& info, const std::string& element,
                                                          std::optional<std::uint32_t> slot, bool after_first,
                                                          Material& m) {
    if (info.index < 0) return std::nullopt;
    if (static_cast<std::size_t>(info.index) >= model_.textures.size()) {
        fail_at(element + ".index", fmt::format("texture {} does not exist (the file has {})", info.index,
                                                model_.textures.size()));
    }
    const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(info.index)];
    const std::string where = fmt::format("textures[{}]", info.index);
    Mapping mapping{info.texCoord, {1.0, 0.0, 0.0, 0.0, 1.0, 0.0}};
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
        mapping.transform = texture_transform(ou, ov, rotation, su, sv);
        if (v.Get("texCoord").IsInt()) mapping.set = v.Get("texCoord").GetNumberAsInt();
    }
    if (mapping.set < 0) {
        fail_at(element + ".texCoord", fmt::format("expected an integer from 0, got {}", mapping.set));
    }
    if (texture.source < 0 || static_cast<std::size_t>(texture.source) >= model_.images.size()) {
        if (texture.source < 0) {
            note_("textures without a source image (or with one of an extension's), rendered without the texture");
            return std::nullopt;
        }
        fail_at(where + ".source", fmt::format("image {} does not exist (the file has {})", texture.source,
                                               model_.images.size()));
    }
    if (!place_on_mapping(mapping, slot, after_first, m)) return std::nullopt;
    Source out;
    out.image = texture.source;
    out.sampler = texture.sampler;
    if (texture.sampler >= 0) {
        if (static_cast<std::size_t>(texture.sampler) >= model_.samplers.size()) {
            fail_at(where + ".sampler", fmt::format("sampler {} does not exist (the file has {})", texture.sampler,
                                                    model_.samplers.size()));
        }
        const tinygltf::Sampler& s = model_.samplers[static_cast<std::size_t>(texture.sampler)];
        out.wrap_s = wrap_mode(s.wrapS);
        out.wrap_t = wrap_mode(s.wrapT);
    }
    return out;
}

bool TextureReader::place_on_mapping(const Mapping& mapping, std::optional<std::uint32_t> slot, bool after_first,
                                     Material& m) {
    if (!after_first) {
        m.uv_transform = mapping.transform;
        m.second_mapping = Material::SecondMapping{};
        sets_ = {mapping.set, -1};
        return true;
    }
    if (mapping.set == sets_.first && mapping.transform == m.uv_transform) return true;
    if (!slot) {
        note_("KHR_materials_pbrSpecularGlossiness textures on different texture coordinates (TEXCOORD_n or "
              "KHR_texture_transform), converted without the specular-glossiness texture");
        return false;
    }
    if (*slot == kernel::MAP_COLOR) {
        note_("a material's colour texture on other texture coordinates (TEXCOORD_n or KHR_texture_transform) than "
              "its first texture, rendered without the colour texture");
        return false;
    }
    Material::SecondMapping& second = m.second_mapping;
    if (second.maps == 0) {
        second.transform = mapping.transform;
        second.own_coordinates = mapping.set != sets_.first;
        sets_.second = mapping.set;
    } else if (mapping.set != sets_.second || mapping.transform != second.transform) {
        note_("a material's textures on more than two mappings of texture coordinates (TEXCOORD_n and "
              "KHR_texture_transform), rendered without the later textures");
        return false;
    }
    second.maps |= 1u << *slot;
    return true;
}

std::size_t TextureReader::encoded_image(int index, Encoding encoding) {
    auto [at, added] = image_of_.try_emplace(index, images_.size());
    if (added) {
        const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
        if (image.image.empty()) fail_at(fmt::format("images[{}]", index), "the image holds no bytes");
        images_.push_back({image.image.data(), image.image.size(), format_name(image), encoding,
                           fmt::format("{}: images[{}]", file_.string(), index)});
    }
    return at->second;
}

std::optional<std::uint32_t> TextureReader::request(const tinygltf::TextureInfo& info, const std::string& element,
                                                    Encoding encoding, double normal_scale, bool normal,
                                                    std::uint32_t slot, Material& m) {
    const std::optional<Source> s = source(info, element, slot, m.textured(), m);
    if (!s) return std::nullopt;
    const auto key = std::tuple{s->image, s->sampler, encoding, normal, normal ? normal_scale : 1.0};
    if (auto it = ticket_of_.find(key); it != ticket_of_.end()) return it->second;
    Ticket ticket;
    ticket.image = encoded_image(s->image, encoding);
    ticket.encoding = encoding;
    ticket.wrap_s = s->wrap_s;
    ticket.wrap_t = s->wrap_t;
    ticket.normal_scale = normal_scale;
    tickets_.push_back(ticket);
    const auto index = static_cast<std::uint32_t>(tickets_.size() - 1);
    ticket_of_.emplace(key, index);
    return index;
}

std::optional<TextureReader::Converted> TextureReader::specular_glossiness(const tinygltf::TextureInfo* diffuse,
                                                                          const tinygltf::TextureInfo* specular_glossiness,
                                                                          const std::string& element,
                                                                          const SpecularGlossiness& factors,
                                                                          double alpha, Material& m) {
    // Converted texel by texel, both textures must read one mapping: the first.
    std::optional<Source> d, s;
    if (diffuse) d = source(*diffuse, element + ".diffuseTexture", std::nullopt, m.textured(), m);
    if (specular_glossiness) {
            s = source(*specular_glossiness, element + ".specularGlossinessTexture", std::nullopt, m.textured() || d, m);
    }
    if (!d && !s) return std::nullopt;
    if (d && s && (d->wrap_s != s->wrap_s || d->wrap_t != s->wrap_t)) {
        note_("KHR_materials_pbrSpecularGlossiness textures with different wrap modes, both converted with the "
              "diffuse texture's");
    }
    const std::array<double, 8> values{factors.diffuse.r,  factors.diffuse.g,  factors.diffuse.b, factors.specular.r,
                                       factors.specular.g, factors.specular.b, factors.glossiness, alpha};
    const auto key = std::tuple{d ? d->image : -1, d ? d->sampler : -1, s ? s->image : -1, s ? s->sampler : -1, values};
    if (auto it = conversion_of_.find(key); it != conversion_of_.end()) return Converted{it->second, it->second + 1};
    // The extension's colours are sRGB, its glossiness (alpha) linear.
    const auto input = [&](const Source& source) {
        return Input{encoded_image(source.image, Encoding::SrgbUnlessFloat), source.wrap_s, source.wrap_t};
    };
    Conversion c;
    if (d) c.diffuse = input(*d);
    if (s) c.specular_glossiness = input(*s);
    c.factors = factors;
    c.alpha = alpha;
    c.element = element;
    c.ticket = static_cast<std::uint32_t>(tickets_.size());
    Ticket ticket;
    ticket.conversion = conversions_.size();
    tickets_.push_back(ticket);
    tickets_.push_back(ticket);
    conversions_.push_back(std::move(c));
    conversion_of_.emplace(key, conversions_.back().ticket);
    return Converted{conversions_.back().ticket, conversions_.back().ticket + 1};
}

std::vector<std::uint32_t> TextureReader::resolve() {
    // The images plain tickets use are decoded into the scene's texels; those only
    // conversions read are decoded apart (convert) and leave no texels behind.
    constexpr std::size_t kNone = ~std::size_t(0);
    std::vector<std::size_t> stored_at(images_.size(), kNone);  // images_ -> `stored`
    std::vector<EncodedImage> to_store;
    for (const Ticket& ticket : tickets_) {
        if (ticket.conversion || stored_at[ticket.image] != kNone) continue;
        stored_at[ticket.image] = to_store.size();
        to_store.push_back(images_[ticket.image]);
    }
    std::vector<TextureImage> stored = decode_textures(to_store, scene_);
    // An image decoded to half floats in one encoding and wanted in the other as well
    // (a 16-bit PNG as colour and as data) is decoded again in that one.
    std::vector<EncodedImage> again;
    std::vector<std::size_t> again_at(images_.size(), kNone);  // images_ -> its second decoding in `stored`
    for (const Ticket& ticket : tickets_) {
        if (ticket.conversion) continue;
        const EncodedImage& image = images_[ticket.image];
        if (ticket.encoding == image.encoding || stored[stored_at[ticket.image]].format != TexelFormat::Half) continue;
        if (again_at[ticket.image] == kNone) {
            again_at[ticket.image] = stored.size() + again.size();
            again.push_back(image);
            again.back().encoding = ticket.encoding;
        }
    }
    for (TextureImage& t : decode_textures(again, scene_)) stored.push_back(std::move(t));
    std::vector<std::uint32_t> out(tickets_.size());
    for (std::size_t i = 0; i < tickets_.size(); ++i) {
        const Ticket& ticket = tickets_[i];
        if (ticket.conversion) continue;
        const bool other = ticket.encoding != images_[ticket.image].encoding;
        TextureImage t = stored[other && again_at[ticket.image] != kNone ? again_at[ticket.image] : stored_at[ticket.image]];
        if (t.format == TexelFormat::Rgba8) t.srgb = ticket.encoding == Encoding::SrgbUnlessFloat;
        t.wrap_s = ticket.wrap_s;
        t.wrap_t = ticket.wrap_t;
        t.normal_scale = ticket.normal_scale;
        out[i] = add_texture_record(scene_, std::move(t));
    }
    // Where in `stored` each image is as the conversions read it (sRGB colour): an
    // 8-bit one in any encoding, a half-float one decoded with its colours sRGB-decoded.
    std::vector<std::size_t> as_srgb(images_.size(), kNone);
    for (std::size_t i = 0; i < images_.size(); ++i) {
        if (stored_at[i] == kNone) continue;
        if (stored[stored_at[i]].format == TexelFormat::Rgba8 || images_[i].encoding == Encoding::SrgbUnlessFloat) {
            as_srgb[i] = stored_at[i];
        } else if (again_at[i] != kNone) {
            as_srgb[i] = again_at[i];
        }
    }
    convert(stored, as_srgb, out);
    return out;
}

void TextureReader::convert(const std::vector<TextureImage>& stored, const std::vector<std::size_t>& stored_as_srgb,
                            std::vector<std::uint32_t>& out) {
    if (conversions_.empty()) return;
    // The images no plain ticket has put in the store, decoded apart, each once, and
    // each dropped when the last conversion that reads it is done.
    constexpr std::size_t kNone = ~std::size_t(0);
    std::vector<std::size_t> apart_at(images_.size(), kNone);
    std::vector<EncodedImage> to_decode;
    std::vector<std::size_t> readers;  // conversions still to read each image apart
    for (const Conversion& c : conversions_) {
        for (const std::optional<Input>& in : {c.diffuse, c.specular_glossiness}) {
            if (!in || stored_as_srgb[in->image] != kNone) continue;
            if (apart_at[in->image] == kNone) {
                apart_at[in->image] = to_decode.size();
                to_decode.push_back(images_[in->image]);
                to_decode.back().encoding = Encoding::SrgbUnlessFloat;
                readers.push_back(0);
            }
            ++readers[apart_at[in->image]];
        }
    }
    std::vector<DecodedImage> apart = decode_images(to_decode, scene_);
    for (const Conversion& c : conversions_) {
        const auto source = [&](const std::optional<Input>& in) -> std::optional<SourceTexture> {
            if (!in) return std::nullopt;
            SourceTexture s;
            if (const std::size_t at = stored_as_srgb[in->image]; at != kNone) {
                s.texture = stored[at];
                s.texture.srgb = s.texture.format == TexelFormat::Rgba8;
                s.words = scene_.texels.words();
            } else {
                const DecodedImage& image = apart[apart_at[in->image]];
                s.texture.width = image.width;
                s.texture.height = image.height;
                s.texture.format = image.format;
                s.texture.srgb = image.srgb;
                s.words = image.words;
            }
            s.texture.wrap_s = in->wrap_s;
            s.texture.wrap_t = in->wrap_t;
            return s;
        };
        const std::optional<SourceTexture> d = source(c.diffuse), sg = source(c.specular_glossiness);
        ConvertedTextures converted = convert_textures(d ? &*d : nullptr, sg ? &*sg : nullptr, c.factors, c.alpha);
        for (const std::optional<Input>& in : {c.diffuse, c.specular_glossiness}) {
            if (in && apart_at[in->image] != kNone && --readers[apart_at[in->image]] == 0) {
                apart[apart_at[in->image]] = DecodedImage();
            }
        }
        const Input& wraps = c.diffuse ? *c.diffuse : *c.specular_glossiness;
        const auto add = [&](DecodedImage&& image, const char* what) {
            const std::string name = fmt::format("{}: {} ({})", file_.string(), c.element, what);
            const std::uint32_t index = add_texture(scene_, std::move(image), name, name);
            scene_.textures[index].wrap_s = wraps.wrap_s;
            scene_.textures[index].wrap_t = wraps.wrap_t;
            return index;
        };
        out[c.ticket] = add(std::move(converted.base_color), "converted to a base colour");
        out[c.ticket + 1] = add(std::move(converted.metallic_roughness), "converted to metallic-roughness");
    }
}

}  // namespace vkrt::gltf
