#include "scene/gltf_file.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <system_error>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene/scene_error.hpp"

namespace vkrt::gltf {
namespace {

// The extensions read (docs/gltf.md); any other the file uses is named in a
// warning, and any other it requires refuses the file.
constexpr std::array<std::string_view, 14> kExtensionsRead = {
    "KHR_lights_punctual",     "KHR_materials_emissive_strength", "KHR_texture_transform",
    "KHR_mesh_quantization",   "KHR_draco_mesh_compression",      "EXT_meshopt_compression",
    "KHR_materials_pbrSpecularGlossiness", "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_volume", "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
    "EXT_mesh_gpu_instancing"};

constexpr std::size_t kGlbHeader = 12;  // magic, version, length
constexpr std::size_t kChunkHeader = 8;  // length, type
constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"

std::uint32_t load_u32(const unsigned char* p) {
    std::uint32_t v;
    std::memcpy(&v, p, 4);  // little-endian, as is every host vkrt builds for
    return v;
}

void store_u32(unsigned char* p, std::uint32_t v) { std::memcpy(p, &v, 4); }

std::vector<unsigned char> read_bytes(const std::filesystem::path& file) {
    const auto fail = [&](const std::string& why) {
        throw SceneError(fmt::format("{}: not a readable glTF file: {}", file.string(), why));
    };
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) fail("not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec) fail(ec.message());
    // tinygltf takes a .glb's size as 32 bits (and its JSON as a string of it).
    if (size > std::numeric_limits<std::uint32_t>::max()) fail("larger than 4 GiB");
    std::vector<unsigned char> bytes(size);
    std::ifstream in(file, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) fail("cannot read it");
    return bytes;
}

// Where a .glb's JSON chunk lies (specification 4.4.3): its length, or none when
// the header does not hold one whole (tinygltf then says what is wrong).
std::optional<std::size_t> glb_json_length(const std::vector<unsigned char>& bytes) {
    if (bytes.size() < kGlbHeader + kChunkHeader) return std::nullopt;
    const std::size_t length = load_u32(bytes.data() + kGlbHeader);
    if (load_u32(bytes.data() + kGlbHeader + 4) != kJsonChunk) return std::nullopt;
    if (length > bytes.size() - kGlbHeader - kChunkHeader) return std::nullopt;
    return length;
}

// The first extension the file requires that vkrt does not read, refused by name.
void check_required(const nlohmann::json& root, const std::filesystem::path& file) {
    const auto required = root.find("extensionsRequired");
    if (required == root.end()) return;
    if (!required->is_array()) {
        throw SceneError(fmt::format("{}: extensionsRequired: expected an array of extension names", file.string()));
    }
    for (std::size_t i = 0; i < required->size(); ++i) {
        const nlohmann::json& name = (*required)[i];
        if (!name.is_string()) {
            throw SceneError(fmt::format("{}: extensionsRequired[{}]: expected an extension name", file.string(), i));
        }
        if (!reads_extension(name.get_ref<const std::string&>())) {
            throw SceneError(fmt::format("{}: the file requires the extension {}, which vkrt does not read",
                                         file.string(), name.get_ref<const std::string&>()));
        }
    }
}

// The .glb `bytes` with `json` as its JSON chunk, padded with spaces (4.4.3.1).
std::vector<unsigned char> replace_json_chunk(const std::vector<unsigned char>& bytes, std::size_t old_length,
                                              std::string json) {
    while (json.size() % 4 != 0) json += ' ';
    const std::size_t rest = kGlbHeader + kChunkHeader + old_length;
    std::vector<unsigned char> out(bytes.begin(), bytes.begin() + kGlbHeader + kChunkHeader);
    out.insert(out.end(), json.begin(), json.end());
    out.insert(out.end(), bytes.begin() + static_cast<std::ptrdiff_t>(rest), bytes.end());
    // The header's total length moves by as much as the chunk did (a wrong one
    // stays wrong, for tinygltf to refuse).
    const std::int64_t total = std::int64_t(load_u32(bytes.data() + 8)) + std::int64_t(json.size()) - std::int64_t(old_length);
    store_u32(out.data() + 8, static_cast<std::uint32_t>(std::clamp<std::int64_t>(total, 0, 0xFFFFFFFF)));
    store_u32(out.data() + kGlbHeader, static_cast<std::uint32_t>(json.size()));
    return out;
}

}  // namespace

bool reads_extension(std::string_view name) {
    return std::find(kExtensionsRead.begin(), kExtensionsRead.end(), name) != kExtensionsRead.end();
}

PreparedFile prepare_file(const std::filesystem::path& file) {
    PreparedFile prepared;
    prepared.bytes = read_bytes(file);
    const std::vector<unsigned char>& bytes = prepared.bytes;
    prepared.binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    std::optional<std::size_t> json_length;
    const unsigned char* json = bytes.data();
    if (prepared.binary) {
        json_length = glb_json_length(bytes);
        json += kGlbHeader + kChunkHeader;
    } else {
        json_length = bytes.size();
    }
    if (!json_length) return prepared;
    nlohmann::json root = nlohmann::json::parse(json, json + *json_length, nullptr, false);
    if (!root.is_object()) return prepared;  // malformed: tinygltf's message says where
    check_required(root, file);
    prepared.draco = take_draco_primitives(root, file.string());
    prepared.meshopt = take_meshopt_views(root, prepared.binary, file.string());
    if (prepared.draco.empty() && prepared.meshopt.placeholders.empty()) return prepared;
    std::string text = root.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (prepared.binary) {
        prepared.bytes = replace_json_chunk(bytes, *json_length, std::move(text));
    } else {
        prepared.bytes.assign(text.begin(), text.end());
    }
    return prepared;
}

void decode_set_aside(tinygltf::Model& model, const PreparedFile& prepared, const std::string& file) {
    decode_meshopt(model, prepared.meshopt, file);
    decode_draco(model, prepared.draco, file);
}

}  // namespace vkrt::gltf
