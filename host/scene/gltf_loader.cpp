#include "scene/gltf_loader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_accessor.hpp"
#include "scene/gltf_file.hpp"
#include "scene/gltf_instancing.hpp"
#include "scene/gltf_spec_gloss.hpp"
#include "scene/gltf_spec_gloss_textures.hpp"
#include "scene/gltf_textures.hpp"
#include "scene/indexed_mesh.hpp"
#include "scene/json_reader.hpp"
#include "scene/limits.hpp"
#include "scene/scene_error.hpp"
#include "scene/vec_math.hpp"

namespace vkrt {
namespace {

using glm::dmat4;
using glm::dvec3;

// The luminous efficacy by which glTF's photometric light units (candela, lux) become
// the renderer's radiometric ones: the definition of the candela, at 555 nm.
constexpr double kLumensPerWatt = 683.0;

// The sky behind a file that brings its own lights: Blender's default world.
constexpr double kLitSceneSky = 0.05;

// A primitive as its mesh holds it, before any node places it.
struct PrimitiveMesh {
    std::string element;  // "meshes[m].primitives[p]", for messages
    IndexedMesh mesh;
    MeshOptions options;
};

// Node placements (a node under each of its parents counts once per path): far more
// than any asset has, few enough to walk in a moment.
constexpr std::size_t kMaxNodeVisits = 100'000;

// A URI's percent escapes decoded (RFC 3986, 2.1), as glTF relative URIs are written.
std::string decode_uri(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// tinygltf only warns about an image file it cannot find; a missing part of the
// asset is an error here, as a missing buffer is.
void check_image_files(const std::filesystem::path& file, const tinygltf::Model& model) {
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const std::string& uri = model.images[i].uri;
        if (uri.empty() || uri.rfind("data:", 0) == 0) continue;
        const std::filesystem::path image = file.parent_path() / decode_uri(uri);
        std::error_code ec;
        if (!std::filesystem::is_regular_file(image, ec)) {
            throw SceneError(fmt::format("{}: images[{}].uri: the image file {} {}", file.string(), i, image.string(),
                                         std::filesystem::exists(image, ec) ? "is not a regular file" : "does not exist"));
        }
    }
}

// tinygltf's own file callbacks open whatever a URI names: its FileExists blocks
// on a FIFO, and its ReadWholeFile takes a directory's end offset for its size
// (2^63 - 1 bytes on ext4) and allocates that much. The asset's files (the glTF
// itself, its buffers and images) are read through these instead, which look
// before they open and take regular files only.
bool path_exists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

bool read_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    const auto fail = [&](const std::string& why) {
        if (err) *err += why;
        return false;
    };
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return fail("not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) return fail(ec.message());
    std::ifstream in(path, std::ios::binary);
    out->resize(size);
    if (!in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
        return fail("cannot read it");
    }
    return true;
}

tinygltf::Model read_model(const std::filesystem::path& file, std::vector<std::string>& warnings) {
    tinygltf::TinyGLTF reader;
    reader.SetImageLoader(gltf::keep_image_bytes, nullptr);
    reader.SetFsCallbacks({&path_exists, &tinygltf::ExpandFilePath, &read_regular_file, &tinygltf::WriteWholeFile, nullptr});
    tinygltf::Model model;
    std::string error, warning;
    // Required extensions refused by name first; compressed parts set aside.
    const gltf::PreparedFile prepared = gltf::prepare_file(file);
    const bool binary = prepared.binary;
    const std::string base_dir = file.parent_path().string();
    const auto size = static_cast<unsigned int>(prepared.bytes.size());
    const bool ok = binary ? reader.LoadBinaryFromMemory(&model, &error, &warning, prepared.bytes.data(), size, base_dir)
                           : reader.LoadASCIIFromString(&model, &error, &warning,
                                                        reinterpret_cast<const char*>(prepared.bytes.data()), size, base_dir);
    const auto lines = [](std::string text) {
        while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
        std::replace(text.begin(), text.end(), '\n', ';');
        return text;
    };
    if (!ok) {
        throw SceneError(fmt::format("{}: not a readable glTF {} file: {}", file.string(), binary ? "binary (.glb)" : "(.gltf)",
                                     error.empty() ? "no reason given" : lines(error)));
    }
    if (!warning.empty()) warnings.push_back(fmt::format("{}: {}", file.string(), lines(warning)));
    gltf::decode_set_aside(model, prepared, file.string());
    check_image_files(file, model);
    return model;
}

class GltfReader {
public:
    GltfReader(std::filesystem::path file, tinygltf::Model model, Scene& scene, bool want_camera)
        : file_(std::move(file)),
          model_(std::move(model)),
          scene_(scene),
          want_camera_(want_camera),
          textures_(model_, file_, scene_, [this](const std::string& what) { note_unsupported(what); }) {}

    // Everything under the default scene's roots, placed by each of `roots` in turn,
    // with the materials and textures made once for all; `after_first`, if any, is
    // told how many triangles the first placement added before any other is made.
    void read(const std::vector<dmat4>& roots, const std::function<void(std::size_t)>& after_first = {}) {
        check_extensions();
        read_materials();
        const std::size_t before = scene_.triangles.size();
        for (const dmat4& root : roots) {
            visits_ = 0;
            for (int node : scene_roots()) visit(node, root, 0);
            if (scene_.triangles.size() == before) fail("the file's scene has no triangles to render");
            if (after_first && &root == &roots.front()) after_first(scene_.triangles.size() - before);
        }
        if (degenerate_ > 0) {
            warn(fmt::format("skipped {} of {} triangles that have zero area", degenerate_, triangles_read_));
        }
        for (const auto& [what, count] : unsupported_) warn(fmt::format("{} ({}): ignored", what, count));
        for (const auto& [mesh, count] : placements_) {
            if (count > 1) {
                scene_.instances.meshes += 1;
                scene_.instances.placements += count;
            }
        }
    }

    bool has_camera() const { return camera_found_; }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw SceneError(fmt::format("{}: {}", file_.string(), what));
    }
    [[noreturn]] void fail_at(const std::string& element, const std::string& what) const {
        throw SceneError(fmt::format("{}: {}: {}", file_.string(), element, what));
    }
    void warn(const std::string& what) { scene_.warnings.push_back(fmt::format("{}: {}", file_.string(), what)); }
    void note_unsupported(const std::string& what) { ++unsupported_[what]; }

    // Those the file requires were checked before tinygltf read it (gltf_file.hpp).
    void check_extensions() {
        for (const std::string& name : model_.extensionsUsed) {
            if (!gltf::reads_extension(name)) warn(fmt::format("the extension {} is not supported; ignored", name));
            if (name == "KHR_mesh_quantization") quantized_ = true;
        }
    }

    // The metallic-roughness factors and textures, the normal map, emission as
    // emissive factor times strength times the emissive texture; the occlusion
    // texture is listed as ignored.
    void read_materials() {
        for (std::size_t i = 0; i < model_.materials.size(); ++i) {
            const tinygltf::Material& g = model_.materials[i];
            const std::string element = fmt::format("materials[{}]", i);
            Material m;
            m.name = g.name.empty() ? element : g.name;
            const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
            // Assigned rather than emplace()d: clang 14 takes the nested struct, its
            // member initializers not yet parsed, as not default-constructible.
            m.metallic_roughness = Material::MetallicRoughness{};
            Material::MetallicRoughness& mr = *m.metallic_roughness;
            const std::vector<double>& base = pbr.baseColorFactor;
            if (base.size() == 4) mr.base_color = color(dvec3(base[0], base[1], base[2]), 1.0, element + ".pbrMetallicRoughness.baseColorFactor");
            mr.metallic = unit(pbr.metallicFactor, element + ".pbrMetallicRoughness.metallicFactor");
            mr.roughness = unit(pbr.roughnessFactor, element + ".pbrMetallicRoughness.roughnessFactor");
            if (base.size() == 4) m.alpha = unit(base[3], element + ".pbrMetallicRoughness.baseColorFactor[3]");
            double strength = 1.0;
            if (auto e = g.extensions.find("KHR_materials_emissive_strength"); e != g.extensions.end()) {
                const tinygltf::Value& s = e->second.Get("emissiveStrength");
                if (s.IsNumber()) strength = s.GetNumberAsDouble();
                if (!(strength >= 0.0 && strength <= 1e6)) {
                    fail_at(element + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
                            fmt::format("expected a number from 0 to 1e6, got {}", strength));
                }
            }
            if (g.emissiveFactor.size() == 3) {
                m.emission = strength * color(dvec3(g.emissiveFactor[0], g.emissiveFactor[1], g.emissiveFactor[2]), 1e6,
                                              element + ".emissiveFactor");
            }
            if (!read_specular_glossiness(g, element, m)) {
                m.texture = textures_.texture(pbr.baseColorTexture, element + ".pbrMetallicRoughness.baseColorTexture",
                                              Encoding::SrgbUnlessFloat, kernel::MAP_COLOR, m);
                m.metallic_roughness_texture = textures_.texture(
                    pbr.metallicRoughnessTexture, element + ".pbrMetallicRoughness.metallicRoughnessTexture",
                    Encoding::Linear, kernel::MAP_METAL_ROUGH, m);
            }
            m.emission_texture =
                textures_.texture(g.emissiveTexture, element + ".emissiveTexture", Encoding::SrgbUnlessFloat,
                                  kernel::MAP_EMISSION, m);
            m.normal_map = textures_.normal_texture(g.normalTexture, element + ".normalTexture", kernel::MAP_NORMAL, m);
            if (g.occlusionTexture.index >= 0) note_unsupported("occlusion maps (not needed by a path tracer)");
            read_alpha_mode(g, element, m);
            read_glass(g, element, m);
            read_clearcoat(g, element, m);
            read_sheen(g, element, m);
            read_specular(g, element, m);
            uv_sets_.push_back(m.textured() ? textures_.uv_sets() : std::pair{0, -1});
            materials_.push_back(static_cast<std::uint32_t>(scene_.materials.size()));
            scene_.materials.push_back(m);
        }
        // The materials hold tickets (gltf_textures.hpp) until every image is decoded.
        const std::vector<std::uint32_t> textures = textures_.resolve();
        for (std::uint32_t index : materials_) {
            Material& m = scene_.materials[index];
            for (std::optional<std::uint32_t>* t : m.texture_slots()) {
                if (*t) *t = textures[**t];
            }
        }
    }

    // alphaMode and alphaCutoff (glTF 2.0, 3.9.4): the opacity is the base colour's
    // alpha (read with it) times its texture's. Opaque ignores both, as the
    // specification says.
    void read_alpha_mode(const tinygltf::Material& g, const std::string& element, Material& m) {
        if (g.alphaMode == "MASK") {
            m.alpha_mode = AlphaMode::Mask;
            if (!(g.alphaCutoff >= 0.0)) {
                fail_at(element + ".alphaCutoff", fmt::format("expected a number of at least 0, got {}", g.alphaCutoff));
            }
            m.alpha_cutoff = g.alphaCutoff;
        } else if (g.alphaMode == "BLEND") {
            m.alpha_mode = AlphaMode::Blend;
        } else if (g.alphaMode != "OPAQUE") {
            fail_at(element + ".alphaMode",
                    fmt::format("unknown alpha mode \"{}\" (expected OPAQUE, MASK or BLEND)", g.alphaMode));
        }
    }

    // Glass (docs/gltf.md): KHR_materials_ior's index, which also sets the
    // dielectric's reflectance; KHR_materials_transmission's factor and texture; and
    // KHR_materials_volume, whose thickness makes the glass the surface of a solid
    // that refracts, where without it the glass is a thin wall, as the extensions
    // specify, and its attenuation absorbs inside the solid. Rough transmission,
    // which is not rendered, is named.
    void read_glass(const tinygltf::Material& g, const std::string& element, Material& m) {
        if (auto e = g.extensions.find("KHR_materials_ior"); e != g.extensions.end()) {
            const tinygltf::Value& v = e->second.Get("ior");
            const double ior = v.IsNumber() ? v.GetNumberAsDouble() : 1.5;
            if (ior == 0.0) {
                note_unsupported("KHR_materials_ior's ior 0 (the default 1.5 is used)");
            } else if (!(ior >= 1.0 && ior <= 1e3)) {
                fail_at(element + ".extensions.KHR_materials_ior.ior",
                        fmt::format("expected a number from 1 to 1000, got {}", ior));
            } else {
                m.ior = ior;
            }
        }
        const auto e = g.extensions.find("KHR_materials_transmission");
        if (e == g.extensions.end() || !m.metallic_roughness) return;
        Material::MetallicRoughness& mr = *m.metallic_roughness;
        const tinygltf::Value& factor = e->second.Get("transmissionFactor");
        if (factor.IsNumber()) {
            mr.transmission = unit(factor.GetNumberAsDouble(),
                                   element + ".extensions.KHR_materials_transmission.transmissionFactor");
        }
        m.transmission_texture = extension_texture(e->second, "transmissionTexture",
                                                   element + ".extensions.KHR_materials_transmission", Encoding::Linear,
                                                   kernel::MAP_TRANSMISSION, m);
        mr.thin = true;
        const auto volume = g.extensions.find("KHR_materials_volume");
        if (volume == g.extensions.end()) return;
        const tinygltf::Value& thickness = volume->second.Get("thicknessFactor");
        const double d = thickness.IsNumber() ? thickness.GetNumberAsDouble() : 0.0;
        if (!(d >= 0.0 && std::isfinite(d))) {
            fail_at(element + ".extensions.KHR_materials_volume.thicknessFactor",
                    fmt::format("expected a number of at least 0, got {}", d));
        }
        mr.thin = d == 0.0;
        const std::string at = element + ".extensions.KHR_materials_volume";
        if (const tinygltf::Value& distance = volume->second.Get("attenuationDistance"); distance.Type() != tinygltf::NULL_TYPE) {
            const double x = distance.IsNumber() ? distance.GetNumberAsDouble() : 0.0;
            if (!(x > 0.0 && std::isfinite(x))) {
                fail_at(at + ".attenuationDistance", "expected a number above 0");
            }
            mr.attenuation_distance = x;
        }
        if (const tinygltf::Value& tint = volume->second.Get("attenuationColor"); tint.Type() != tinygltf::NULL_TYPE) {
            mr.attenuation_color = unit_color(tint, at + ".attenuationColor");
        }
        // A thin wall has no inside to absorb in (the extension ignores the volume then).
        if (mr.thin) {
            mr.attenuation_color = dvec3(1.0);
            mr.attenuation_distance = std::numeric_limits<double>::infinity();
        }
    }

    // KHR_materials_clearcoat's factors and textures: a clear coat over the material
    // (kernel/lobes/coat.glsl), with its own normal map (without one it lies on the
    // surface's normal, not the material's mapped one).
    void read_clearcoat(const tinygltf::Material& g, const std::string& element, Material& m) {
        const auto e = g.extensions.find("KHR_materials_clearcoat");
        if (e == g.extensions.end() || !m.metallic_roughness) return;
        const std::string at = element + ".extensions.KHR_materials_clearcoat";
        Material::MetallicRoughness& mr = *m.metallic_roughness;
        if (const tinygltf::Value& v = e->second.Get("clearcoatFactor"); v.IsNumber()) {
            mr.clearcoat = unit(v.GetNumberAsDouble(), at + ".clearcoatFactor");
        }
        if (const tinygltf::Value& v = e->second.Get("clearcoatRoughnessFactor"); v.IsNumber()) {
            mr.clearcoat_roughness = unit(v.GetNumberAsDouble(), at + ".clearcoatRoughnessFactor");
        }
        m.clearcoat_texture = extension_texture(e->second, "clearcoatTexture", at, Encoding::Linear, kernel::MAP_COAT, m);
        m.clearcoat_roughness_texture = extension_texture(e->second, "clearcoatRoughnessTexture", at, Encoding::Linear,
                                                          kernel::MAP_COAT_ROUGH, m);
        m.clearcoat_normal_map =
            extension_normal_texture(e->second, "clearcoatNormalTexture", at, kernel::MAP_COAT_NORMAL, m);
    }

    // KHR_materials_sheen's factors and textures: sheen over the material, under its
    // coat (kernel/lobes/sheen.glsl).
    void read_sheen(const tinygltf::Material& g, const std::string& element, Material& m) {
        const auto e = g.extensions.find("KHR_materials_sheen");
        if (e == g.extensions.end() || !m.metallic_roughness) return;
        const std::string at = element + ".extensions.KHR_materials_sheen";
        Material::MetallicRoughness& mr = *m.metallic_roughness;
        if (const tinygltf::Value& v = e->second.Get("sheenColorFactor"); v.Type() != tinygltf::NULL_TYPE) {
            mr.sheen_color = unit_color(v, at + ".sheenColorFactor");
        }
        if (const tinygltf::Value& v = e->second.Get("sheenRoughnessFactor"); v.IsNumber()) {
            mr.sheen_roughness = unit(v.GetNumberAsDouble(), at + ".sheenRoughnessFactor");
        }
        m.sheen_color_texture = extension_texture(e->second, "sheenColorTexture", at, Encoding::SrgbUnlessFloat,
                                                  kernel::MAP_SHEEN, m);
        m.sheen_roughness_texture = extension_texture(e->second, "sheenRoughnessTexture", at, Encoding::Linear,
                                                      kernel::MAP_SHEEN_ROUGH, m);
    }

    // KHR_materials_specular's factors and textures: the dielectric's specular layer
    // (scene.hpp; kernel/lobes/fresnel.glsl), and on glass its layer
    // (kernel/lobes/glass.glsl glass_split).
    void read_specular(const tinygltf::Material& g, const std::string& element, Material& m) {
        const auto e = g.extensions.find("KHR_materials_specular");
        if (e == g.extensions.end() || !m.metallic_roughness) return;
        const std::string at = element + ".extensions.KHR_materials_specular";
        Material::MetallicRoughness& mr = *m.metallic_roughness;
        if (const tinygltf::Value& v = e->second.Get("specularFactor"); v.Type() != tinygltf::NULL_TYPE) {
            mr.specular = unit(v.IsNumber() ? v.GetNumberAsDouble() : -1.0, at + ".specularFactor");
        }
        if (const tinygltf::Value& v = e->second.Get("specularColorFactor"); v.Type() != tinygltf::NULL_TYPE) {
            if (!v.IsArray() || v.ArrayLen() != 3) fail_at(at + ".specularColorFactor", "expected 3 numbers of at least 0");
            dvec3 c;
            for (int i = 0; i < 3; ++i) c[i] = v.Get(i).IsNumber() ? v.Get(i).GetNumberAsDouble() : -1.0;
            mr.specular_color = color(c, 1e6, at + ".specularColorFactor");
        }
        m.specular_texture = extension_texture(e->second, "specularTexture", at, Encoding::Linear, kernel::MAP_SPECULAR, m);
        m.specular_color_texture = extension_texture(e->second, "specularColorTexture", at, Encoding::SrgbUnlessFloat,
                                                     kernel::MAP_SPECULAR_COLOR, m);
    }

    // KHR_materials_pbrSpecularGlossiness, which takes the place of
    // pbrMetallicRoughness where a material has it: its factors converted
    // (gltf_spec_gloss.hpp), or with textures, the textures converted texel by texel
    // with the factors multiplied in (gltf_spec_gloss_textures.hpp), the material's
    // own factors then 1. Whether the material has it.
    bool read_specular_glossiness(const tinygltf::Material& g, const std::string& element, Material& m) {
        const auto e = g.extensions.find("KHR_materials_pbrSpecularGlossiness");
        if (e == g.extensions.end()) return false;
        const std::string at = element + ".extensions.KHR_materials_pbrSpecularGlossiness";
        double alpha = 1.0;
        const gltf::SpecularGlossiness factors = gltf::read_specular_glossiness(e->second, at, file_.string(), alpha);
        m.metallic_roughness = gltf::to_metallic_roughness(factors);
        m.alpha = alpha;
        const auto diffuse = gltf::read_texture_info(e->second, "diffuseTexture", at, file_.string());
        const auto specular = gltf::read_texture_info(e->second, "specularGlossinessTexture", at, file_.string());
        const auto converted = textures_.specular_glossiness(diffuse ? &*diffuse : nullptr,
                                                             specular ? &*specular : nullptr, at, factors, alpha, m);
        if (converted) {
            m.metallic_roughness = Material::MetallicRoughness{dvec3(1.0), 1.0, 1.0};
            m.alpha = 1.0;  // in the converted texture's alpha
            m.texture = converted->base_color;
            m.metallic_roughness_texture = converted->metallic_roughness;
        }
        return true;
    }

    // The texture an extension's textureInfo `key` names (its index, texCoord and
    // KHR_texture_transform), read as the core material's textures are; none when the
    // extension has no such key.
    std::optional<std::uint32_t> extension_texture(const tinygltf::Value& extension, const char* key,
                                                   const std::string& at_extension, Encoding encoding,
                                                   std::uint32_t slot, Material& m) {
        if (!extension.Has(key)) return std::nullopt;
        const std::string at = at_extension + "." + key;
        return textures_.texture(texture_info(extension.Get(key), at), at, encoding, slot, m);
    }

    // The same for a normalTextureInfo (its scale, 1 when absent).
    std::optional<std::uint32_t> extension_normal_texture(const tinygltf::Value& extension, const char* key,
                                                          const std::string& at_extension, std::uint32_t slot,
                                                          Material& m) {
        if (!extension.Has(key)) return std::nullopt;
        const std::string at = at_extension + "." + key;
        const tinygltf::Value& t = extension.Get(key);
        const tinygltf::TextureInfo plain = texture_info(t, at);
        tinygltf::NormalTextureInfo info;
        info.index = plain.index;
        info.texCoord = plain.texCoord;
        info.extensions = plain.extensions;
        if (t.Has("scale")) {
            if (!t.Get("scale").IsNumber()) fail_at(at + ".scale", "expected a number");
            info.scale = t.Get("scale").GetNumberAsDouble();
        }
        return textures_.normal_texture(info, at, slot, m);
    }

    // A textureInfo object at `at`: its index, texCoord and KHR_texture_transform.
    tinygltf::TextureInfo texture_info(const tinygltf::Value& t, const std::string& at) const {
        if (!t.IsObject() || !t.Get("index").IsInt()) fail_at(at, "expected a textureInfo with an \"index\"");
        tinygltf::TextureInfo info;
        info.index = t.Get("index").GetNumberAsInt();
        if (t.Get("texCoord").IsInt()) info.texCoord = t.Get("texCoord").GetNumberAsInt();
        if (t.Has("extensions") && t.Get("extensions").Has("KHR_texture_transform")) {
            info.extensions["KHR_texture_transform"] = t.Get("extensions").Get("KHR_texture_transform");
        }
        return info;
    }

    // An extension's colour: an array of 3 numbers from 0 to 1, each named when it is not.
    dvec3 unit_color(const tinygltf::Value& v, const std::string& element) const {
        if (!v.IsArray() || v.ArrayLen() != 3) fail_at(element, "expected 3 numbers from 0 to 1");
        dvec3 out;
        for (int i = 0; i < 3; ++i) {
            const tinygltf::Value& c = v.Get(i);
            out[i] = unit(c.IsNumber() ? c.GetNumberAsDouble() : -1.0, fmt::format("{}[{}]", element, i));
        }
        return out;
    }

    double unit(double v, const std::string& element) const {
        if (!(v >= 0.0 && v <= 1.0)) fail_at(element, fmt::format("expected a number from 0 to 1, got {}", v));
        return v;
    }

    // A colour whose components lie in [0, hi]: 1 for a base colour, 1e6 for emission.
    dvec3 color(dvec3 c, double hi, const std::string& element) const {
        for (int k = 0; k < 3; ++k) {
            if (!(c[k] >= 0.0 && c[k] <= hi)) fail_at(element, fmt::format("expected components from 0 to {}, got {}", hi, c[k]));
        }
        return c;
    }

    // The glTF default material (specification 3.9.6): white, metallic and rough.
    std::uint32_t default_material() {
        if (!default_material_) {
            Material m;
            m.name = "glTF default";
            m.metallic_roughness = Material::MetallicRoughness{.base_color = dvec3(1.0), .metallic = 1.0, .roughness = 1.0};
            default_material_ = static_cast<std::uint32_t>(scene_.materials.size());
            scene_.materials.push_back(m);
        }
        return *default_material_;
    }

    std::vector<int> scene_roots() const {
        if (model_.scenes.empty()) {
            // No scene: the specification leaves it to the client; every node no
            // other node has as a child is a root.
            std::vector<bool> child(model_.nodes.size(), false);
            for (const tinygltf::Node& n : model_.nodes) {
                for (int c : n.children) {
                    if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[static_cast<std::size_t>(c)] = true;
                }
            }
            std::vector<int> roots;
            for (std::size_t i = 0; i < child.size(); ++i) {
                if (!child[i]) roots.push_back(static_cast<int>(i));
            }
            return roots;
        }
        const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (static_cast<std::size_t>(s) >= model_.scenes.size()) {
            fail_at("scene", fmt::format("scene {} does not exist (the file has {})", s, model_.scenes.size()));
        }
        return model_.scenes[static_cast<std::size_t>(s)].nodes;
    }

    dmat4 local_matrix(const tinygltf::Node& n, const std::string& element) const {
        dmat4 m(1.0);
        if (n.matrix.size() == 16) {
            for (int c = 0; c < 4; ++c) {
                for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[static_cast<std::size_t>(4 * c + r)];
            }
        } else {
            const auto given = [](const std::vector<double>& v, auto none) {
                decltype(none) out = none;
                if (v.size() == std::size_t(out.length())) {
                    for (int i = 0; i < out.length(); ++i) out[i] = v[std::size_t(i)];
                }
                return out;
            };
            const std::optional<dmat4> trs = gltf::compose_trs(given(n.translation, dvec3(0.0)),
                                                               given(n.rotation, glm::dvec4(0.0, 0.0, 0.0, 1.0)),
                                                               given(n.scale, dvec3(1.0)));
            if (!trs) fail_at(element + ".rotation", "expected a non-zero quaternion");
            m = *trs;
        }
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                if (!std::isfinite(m[c][r])) fail_at(element, "the node's transform is not finite");
            }
        }
        return m;
    }

    void visit(int index, const dmat4& parent, int depth) {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) {
            fail(fmt::format("node {} does not exist (the file has {})", index, model_.nodes.size()));
        }
        const std::string element = fmt::format("nodes[{}]", index);
        // A node hierarchy is a forest; deeper than the nodes there are means a cycle.
        if (static_cast<std::size_t>(depth) > model_.nodes.size()) fail_at(element, "the node is its own ancestor");
        // Nodes listed as children of several parents are visited once per path, and
        // a few dozen nodes that each list the next twice would take 2^N visits.
        if (++visits_ > kMaxNodeVisits) {
            fail(fmt::format("the node hierarchy places more than {} nodes (nodes listed as the children of "
                             "several parents are placed once for each)",
                             kMaxNodeVisits));
        }
        const tinygltf::Node& n = model_.nodes[static_cast<std::size_t>(index)];
        const dmat4 world = parent * local_matrix(n, element);
        if (n.mesh >= 0) {
            // EXT_mesh_gpu_instancing places the node's mesh once per instance, each
            // instance's own transform applied before the node's.
            if (auto e = n.extensions.find("EXT_mesh_gpu_instancing"); e != n.extensions.end()) {
                const std::vector<dmat4> instances =
                    gltf::read_gpu_instances(model_, e->second, {file_.string(), element + ".extensions.EXT_mesh_gpu_instancing"},
                                             quantized_);
                count_instances(n.mesh, instances.size(), element);
                for (std::size_t i = 0; i < instances.size(); ++i) {
                    add_mesh_instance(n.mesh, world * instances[i], fmt::format("{} (instance {})", element, i));
                }
            } else {
                add_mesh_instance(n.mesh, world, element);
            }
        }
        if (n.skin >= 0 || !n.weights.empty()) note_unsupported("skins and morph targets (the mesh is used at rest)");
        if (n.camera >= 0 && want_camera_ && !camera_found_) read_camera(n.camera, world, element);
        if (auto light = n.extensions.find("KHR_lights_punctual"); light != n.extensions.end()) {
            read_light(light->second, world, element);
        }
        for (int child : n.children) visit(child, world, depth + 1);
    }

    // EXT_mesh_gpu_instancing's instances become copies of their mesh (docs/gltf.md),
    // so what they add up to is bounded before any copy is made.
    void count_instances(int mesh_index, std::size_t count, const std::string& node) {
        std::size_t faces = 0;
        for (const std::optional<PrimitiveMesh>& p : mesh_primitives(mesh_index, node)) {
            if (p) faces += p->mesh.faces.size();
        }
        instances_ += count;
        instanced_triangles_ += count * faces;
        if (instances_ > limits::kMaxInstances || instanced_triangles_ > limits::kMaxInstancedTriangles) {
            fail_at(node + ".extensions.EXT_mesh_gpu_instancing",
                    fmt::format("the file's instances add up to {} copies holding {} triangles; vkrt copies each "
                                "instance's mesh, and takes at most {} instances and {} triangles in them",
                                instances_, instanced_triangles_, limits::kMaxInstances, limits::kMaxInstancedTriangles));
        }
    }

    // The mesh's primitives in its own space, read (and decompressed) on first use;
    // none for those that are not triangles.
    const std::vector<std::optional<PrimitiveMesh>>& mesh_primitives(int mesh_index, const std::string& node) {
        const tinygltf::Mesh& mesh = mesh_at(mesh_index, node);
        const auto [found, first] = primitives_.try_emplace(mesh_index);
        if (!first) return found->second;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = mesh.primitives[p];
            const bool triangles = prim.mode == TINYGLTF_MODE_TRIANGLES || prim.mode == -1;
            found->second.push_back(triangles ? std::optional(read_primitive(
                                                    prim, fmt::format("meshes[{}].primitives[{}]", mesh_index, p)))
                                              : std::nullopt);
        }
        return found->second;
    }

    // The node's mesh `mesh_index`, which must exist.
    const tinygltf::Mesh& mesh_at(int mesh_index, const std::string& node) const {
        if (mesh_index < 0 || static_cast<std::size_t>(mesh_index) >= model_.meshes.size()) {
            fail_at(node + ".mesh", fmt::format("mesh {} does not exist (the file has {})", mesh_index, model_.meshes.size()));
        }
        return model_.meshes[static_cast<std::size_t>(mesh_index)];
    }

    void add_mesh_instance(int mesh_index, const dmat4& world, const std::string& node) {
        const tinygltf::Mesh& mesh = mesh_at(mesh_index, node);
        const std::optional<Transform> t = affine_transform(glm::dmat3(world), dvec3(world[3]));
        if (!t) fail_at(node, "the node's transform flattens its mesh (determinant 0)");
        ++placements_[mesh_index];
        const std::vector<std::optional<PrimitiveMesh>>& primitives = mesh_primitives(mesh_index, node);
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            if (!primitives[p]) {
                note_unsupported("primitives that are not TRIANGLES (points, lines, strips, fans)");
                continue;
            }
            if (!mesh.primitives[p].targets.empty()) note_unsupported("skins and morph targets (the mesh is used at rest)");
            place_primitive(*primitives[p], *t);
        }
    }

    // The primitive's vertex attribute `name`, read by `read`, one value per position
    // (`positions` of them); empty when the primitive has none. A count that differs
    // refuses the file, naming the attribute and what it holds (`what`).
    template <typename Read>
    auto read_attribute(const tinygltf::Primitive& prim, const std::string& element, const std::string& name,
                        std::string_view what, std::size_t positions, Read read) {
        using Values = decltype(read(0, gltf::Origin{}));
        const auto found = prim.attributes.find(name);
        if (found == prim.attributes.end()) return Values{};
        const std::string path = element + ".attributes." + name;
        Values values = read(found->second, gltf::Origin{file_.string(), path});
        if (values.size() != positions) fail_at(path, fmt::format("{} {} for {} positions", values.size(), what, positions));
        return values;
    }

    // The primitive in its mesh's own space, with the options its triangles take.
    PrimitiveMesh read_primitive(const tinygltf::Primitive& prim, const std::string& element) {
        const auto position = prim.attributes.find("POSITION");
        if (position == prim.attributes.end()) fail_at(element + ".attributes", "no POSITION attribute");
        IndexedMesh mesh;
        // KHR_mesh_quantization lets positions and texture coordinates be plain integers.
        const gltf::Integers quantizable = quantized_ ? gltf::Integers::Quantized : gltf::Integers::Quantizable;
        mesh.positions =
            gltf::read_vec3(model_, position->second, {file_.string(), element + ".attributes.POSITION"}, quantizable);
        const std::size_t n = mesh.positions.size();
        mesh.normals = read_attribute(prim, element, "NORMAL", "normals", n, [&](int a, const gltf::Origin& o) {
            return gltf::read_vec3(model_, a, o);
        });
        mesh.tangents = read_attribute(prim, element, "TANGENT", "tangents", n, [&](int a, const gltf::Origin& o) {
            return gltf::read_vec4(model_, a, o);
        });
        // The texture coordinates its material's textures read (TEXCOORD_0 unless they
        // say otherwise), and those of its second mapping where that reads another set.
        const bool known = prim.material >= 0 && static_cast<std::size_t>(prim.material) < uv_sets_.size();
        const auto [first_set, second_set] = known ? uv_sets_[static_cast<std::size_t>(prim.material)] : std::pair{0, -1};
        const auto read_uvs = [&](int a, const gltf::Origin& o) { return gltf::read_vec2(model_, a, o, quantizable); };
        mesh.uvs = read_attribute(prim, element, fmt::format("TEXCOORD_{}", first_set), "texture coordinates", n, read_uvs);
        if (second_set >= 0 && second_set != first_set) {
            mesh.second_uvs =
                read_attribute(prim, element, fmt::format("TEXCOORD_{}", second_set), "texture coordinates", n, read_uvs);
        }
        mesh.colors = read_attribute(prim, element, "COLOR_0", "colours", n, [&](int a, const gltf::Origin& o) {
            return gltf::read_colors(model_, a, o);
        });
        if (mesh.positions.size() > std::numeric_limits<std::uint32_t>::max()) fail_at(element, "too many vertices");
        const auto vertices = static_cast<std::uint32_t>(mesh.positions.size());
        std::vector<std::uint32_t> indices;
        if (prim.indices >= 0) {
            indices = gltf::read_indices(model_, prim.indices, vertices, {file_.string(), element + ".indices"});
        } else {
            indices.resize(vertices);
            for (std::uint32_t i = 0; i < vertices; ++i) indices[i] = i;
        }
        if (indices.size() % 3 != 0) {
            fail_at(element + (prim.indices >= 0 ? ".indices" : ".attributes.POSITION"),
                    fmt::format("{} vertices do not make whole triangles", indices.size()));
        }
        const bool smooth = !mesh.normals.empty();
        for (std::size_t i = 0; i < indices.size(); i += 3) {
            IndexedMesh::Face f;
            f.position = {indices[i], indices[i + 1], indices[i + 2]};
            if (smooth) f.normal = f.position;
            if (!mesh.uvs.empty()) f.uv = f.position;
            if (!mesh.second_uvs.empty()) f.second_uv = f.position;
            if (!mesh.colors.empty()) f.color = f.position;
            if (!mesh.tangents.empty()) f.tangent = f.position;
            mesh.faces.push_back(f);
        }
        MeshOptions options;
        options.smooth = smooth;
        if (prim.material >= 0) {
            if (static_cast<std::size_t>(prim.material) >= materials_.size()) {
                fail_at(element + ".material", fmt::format("material {} does not exist (the file has {})", prim.material,
                                                           materials_.size()));
            }
            options.material = materials_[static_cast<std::size_t>(prim.material)];
        } else {
            options.material = default_material();
        }
        return {element, std::move(mesh), std::move(options)};
    }

    // A copy of the primitive, moved by `t`, added to the scene.
    void place_primitive(const PrimitiveMesh& primitive, const Transform& t) {
        IndexedMesh mesh = primitive.mesh;
        transform_mesh(mesh, t);
        if (const std::optional<dvec3> p = vertex_beyond_limit(mesh)) {
            fail_at(primitive.element, fmt::format("a vertex, placed by its nodes, lies at {}, beyond the largest "
                                                   "coordinate allowed ({})",
                                                   json::format_vec3(*p), json::kMaxMagnitude));
        }
        triangles_read_ += mesh.faces.size();
        degenerate_ += append_mesh(mesh, primitive.options, scene_);
    }

    void read_camera(int index, const dmat4& world, const std::string& node) {
        if (static_cast<std::size_t>(index) >= model_.cameras.size()) {
            fail_at(node + ".camera", fmt::format("camera {} does not exist (the file has {})", index, model_.cameras.size()));
        }
        const tinygltf::Camera& c = model_.cameras[static_cast<std::size_t>(index)];
        if (c.type != "perspective") {
            note_unsupported("orthographic cameras (the view is framed instead)");
            return;
        }
        const double fov = glm::degrees(c.perspective.yfov);
        if (!(fov > 0.0 && fov < 180.0)) {
            fail_at(fmt::format("cameras[{}].perspective.yfov", index),
                    fmt::format("expected an angle between 0 and pi, got {}", c.perspective.yfov));
        }
        Camera& cam = scene_.camera;
        cam.fov = fov;
        cam.eye = dvec3(world * glm::dvec4(0, 0, 0, 1));
        const dvec3 forward = glm::dmat3(world) * dvec3(0, 0, -1);
        const dvec3 up = glm::dmat3(world) * dvec3(0, 1, 0);
        if (!is_nonzero(forward) || parallel_or_zero(forward, up, 1e-9)) fail_at(node, "the camera's node flattens its view");
        cam.look_at = cam.eye + robust_normalize(forward);
        cam.up = robust_normalize(up);
        if (c.perspective.aspectRatio > 0.0) {
            const double aspect = std::clamp(c.perspective.aspectRatio, 1.0 / 64.0, 64.0);
            cam.width = 800;
            cam.height = static_cast<std::uint32_t>(std::max(1.0, std::round(800.0 / aspect)));
        }
        camera_found_ = true;
    }

    void read_light(const tinygltf::Value& extension, const dmat4& world, const std::string& node) {
        const tinygltf::Value& index = extension.Get("light");
        if (!index.IsNumber()) fail_at(node + ".extensions.KHR_lights_punctual", "no light index");
        const int i = index.GetNumberAsInt();
        if (i < 0 || static_cast<std::size_t>(i) >= model_.lights.size()) {
            fail_at(node + ".extensions.KHR_lights_punctual.light",
                    fmt::format("light {} does not exist (the file has {})", i, model_.lights.size()));
        }
        const tinygltf::Light& l = model_.lights[static_cast<std::size_t>(i)];
        const std::string element = fmt::format("extensions.KHR_lights_punctual.lights[{}]", i);
        Light p;
        if (l.type == "spot") {
            p.type = LightType::Spot;
        } else if (l.type == "directional") {
            p.type = LightType::Directional;
        } else if (l.type != "point") {
            note_unsupported(fmt::format("{} lights", l.type));
            return;
        }
        // The node places a point or spot light; a spot or directional light shines
        // down the node's -z axis (its scale aside: the direction is made unit).
        if (p.type != LightType::Directional) p.position = dvec3(world * glm::dvec4(0, 0, 0, 1));
        if (p.type != LightType::Point) {
            const dvec3 d = glm::dmat3(world) * dvec3(0, 0, -1);
            if (!is_nonzero(d) || !std::isfinite(max_abs(d))) {
                fail_at(node, fmt::format("the node's transform flattens its {} light's direction (its -z axis)", l.type));
            }
            p.direction = robust_normalize(d);
        }
        if (p.type == LightType::Spot) read_cone(l.spot, element + ".spot", p);
        if (l.color.size() == 3) p.color = color(dvec3(l.color[0], l.color[1], l.color[2]), 1e6, element + ".color");
        if (!(l.intensity >= 0.0 && std::isfinite(l.intensity))) fail_at(element + ".intensity", "expected a number >= 0");
        // Candela (lux for a directional light) to radiant intensity in watts per
        // steradian (irradiance in watts per square metre) at 683 lumens per watt, as
        // Blender's importer converts them (decision 0036): a point light of I cd
        // lights a surface facing it at r metres with I / 683 / r^2.
        p.intensity = l.intensity / kLumensPerWatt;
        if (l.range > 0.0) note_unsupported("light ranges (lights reach everywhere)");
        scene_.lights.push_back(p);
    }

    // A spot light's cone: 0 <= innerConeAngle < outerConeAngle <= pi/2 (tinygltf
    // fills in the defaults, 0 and pi/4). An outer angle above pi/2 by no more than
    // kAngleSlack is pi/2 written with too few digits (1.5708), and taken as pi/2.
    void read_cone(const tinygltf::SpotLight& spot, const std::string& element, Light& out) const {
        constexpr double kHalfPi = 1.57079632679489661923;
        constexpr double kAngleSlack = 1e-5;
        const double outer = spot.outerConeAngle, inner = spot.innerConeAngle;
        if (!(outer > 0.0 && outer <= kHalfPi + kAngleSlack)) {
            fail_at(element + ".outerConeAngle", fmt::format("expected an angle above 0 and at most pi/2, got {}", outer));
        }
        if (!(inner >= 0.0 && inner < outer)) {
            fail_at(element + ".innerConeAngle",
                    fmt::format("expected an angle from 0 to below outerConeAngle ({}), got {}", outer, inner));
        }
        out.inner_angle = inner;
        out.outer_angle = std::min(outer, kHalfPi);
    }

    std::filesystem::path file_;
    tinygltf::Model model_;
    Scene& scene_;
    std::vector<std::uint32_t> materials_;  // glTF material -> scene material
    std::vector<std::pair<int, int>> uv_sets_;  // glTF material -> the TEXCOORD_<n> of its mappings (-1: none)
    std::optional<std::uint32_t> default_material_;
    std::map<std::string, std::size_t> unsupported_;  // what the image will not show -> how many, said once
    std::size_t visits_ = 0;
    std::map<int, std::size_t> placements_;  // of each mesh, by any node or instance
    std::size_t instances_ = 0;  // EXT_mesh_gpu_instancing's, and the triangles they copy
    std::size_t instanced_triangles_ = 0;
    // Each mesh's primitives as read, by primitive index, so that a mesh placed many
    // times is read (and decompressed) once.
    std::map<int, std::vector<std::optional<PrimitiveMesh>>> primitives_;
    std::size_t degenerate_ = 0;
    std::size_t triangles_read_ = 0;
    bool want_camera_ = true;
    bool camera_found_ = false;
    bool quantized_ = false;  // the file uses KHR_mesh_quantization
    gltf::TextureReader textures_;  // after model_, file_ and scene_, which it refers to
};

}  // namespace

void frame_scene(Scene& scene) {
    dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const Triangle& t : scene.triangles) {
        for (const dvec3& v : t.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    }
    const dvec3 centre = 0.5 * lo + 0.5 * hi;  // halves first: no overflow at 1e308
    // The box's circumscribed sphere (triangles of zero area are not loaded, so it
    // has a size; the floor only keeps the distance finite).
    const double radius = std::max(glm::length(0.5 * hi - 0.5 * lo), 1e-12 * (1.0 + glm::length(centre)));
    Camera& cam = scene.camera;
    cam.fov = 40.0;
    // The sphere fills the narrower of the view's two angles.
    const double half_vertical = glm::radians(cam.fov / 2.0);
    const double aspect = double(cam.width) / double(cam.height);
    const double half_narrow = aspect >= 1.0 ? half_vertical : std::atan(std::tan(half_vertical) * aspect);
    const double distance = radius / std::sin(half_narrow);
    cam.eye = centre + dvec3(0.0, 0.0, distance);
    cam.look_at = centre;
    cam.up = dvec3(0, 1, 0);
    cam.framed = true;
}

namespace {

}  // namespace

Scene load_gltf_scene(const std::filesystem::path& file) {
    Scene scene;
    scene.source = file;
    scene.camera.width = 800;
    scene.camera.height = 600;
    tinygltf::Model model = read_model(file, scene.warnings);
    GltfReader reader(file, std::move(model), scene, true);
    reader.read({dmat4(1.0)});
    if (!reader.has_camera()) frame_scene(scene);
    // Global mode with its defaults (docs/gltf.md): 64 samples a pixel, and a uniform
    // sky as the environment: white, as viewers light a model, when the file brings no
    // lights of its own (emissive materials are details such as indicator lamps, not
    // the scene's lighting); Blender's default world grey when it does.
    scene.render.mode = RenderMode::Global;
    scene.render.jitter = true;
    scene.render.spp = 64;
    scene.render.background = dvec3(scene.lights.empty() ? 1.0 : kLitSceneSky);
    return scene;
}

void add_gltf(const std::filesystem::path& file, const std::vector<Transform>& placements, Scene& scene,
              const std::function<void(std::size_t triangles)>& after_first) {
    std::vector<dmat4> roots;
    for (const Transform& t : placements) {
        dmat4 root(t.linear);
        root[3] = glm::dvec4(t.translate, 1.0);
        roots.push_back(root);
    }
    GltfReader reader(file, read_model(file, scene.warnings), scene, false);
    reader.read(roots, after_first);
}

}  // namespace vkrt
