#include "scene/gltf_meshopt.hpp"

#include <algorithm>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene/scene_error.hpp"

namespace vkrt::gltf {
namespace {

constexpr const char* kName = "EXT_meshopt_compression";

// Each mode's stream spends at least 1/64 of a byte on a decoded byte (the
// extension's Appendix A): ATTRIBUTES 2 header bits for each 16 bytes of a byte
// lane, TRIANGLES a code byte for each 3 indices (12 bytes at most), INDICES a
// byte for each index. A view that claims more would only allocate for nothing.
constexpr std::size_t kMaxExpansion = 64;

// A one-byte buffer in place of a fallback buffer's missing data.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";

// An element of the JSON being read, named for messages.
struct Node {
    const nlohmann::json& json;
    std::string element;
};

[[noreturn]] void fail(const std::string& file, const std::string& element, const std::string& what) {
    throw SceneError(fmt::format("{}: {}: {}", file, element, what));
}

std::optional<std::size_t> count_member(const Node& node, const char* key, bool required, const std::string& file) {
    const auto it = node.json.find(key);
    if (it == node.json.end()) {
        if (required) fail(file, node.element, fmt::format("no {}", key));
        return std::nullopt;
    }
    if (!it->is_number_unsigned()) fail(file, node.element + "." + key, "expected an integer >= 0");
    const std::uint64_t v = it->get<std::uint64_t>();
    if (v > std::numeric_limits<std::size_t>::max() / 2) fail(file, node.element + "." + key, "too large");
    return static_cast<std::size_t>(v);
}

MeshoptView::Mode read_mode(const Node& ext, const std::string& file) {
    const auto it = ext.json.find("mode");
    if (it == ext.json.end()) fail(file, ext.element, "no mode");
    if (*it == "ATTRIBUTES") return MeshoptView::Mode::Attributes;
    if (*it == "TRIANGLES") return MeshoptView::Mode::Triangles;
    if (*it == "INDICES") return MeshoptView::Mode::Indices;
    fail(file, ext.element + ".mode", fmt::format("expected ATTRIBUTES, TRIANGLES or INDICES, got {}", it->dump()));
}

MeshoptView::Filter read_filter(const Node& ext, const std::string& file) {
    const auto it = ext.json.find("filter");
    if (it == ext.json.end() || *it == "NONE") return MeshoptView::Filter::None;
    if (*it == "OCTAHEDRAL") return MeshoptView::Filter::Octahedral;
    if (*it == "QUATERNION") return MeshoptView::Filter::Quaternion;
    if (*it == "EXPONENTIAL") return MeshoptView::Filter::Exponential;
    fail(file, ext.element + ".filter",
         fmt::format("expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL, got {}", it->dump()));
}

// The extension's rules on a view's layout ("JSON schema updates"), which
// libmeshoptimizer asserts rather than checks.
void check_layout(const MeshoptView& v, const nlohmann::json& parent, const std::string& element,
                  const std::string& file) {
    using Mode = MeshoptView::Mode;
    using Filter = MeshoptView::Filter;
    const std::size_t stride = v.byte_stride;
    if (v.mode == Mode::Attributes && (stride == 0 || stride % 4 != 0 || stride > 256)) {
        fail(file, element + ".byteStride", fmt::format("ATTRIBUTES take a multiple of 4 from 4 to 256, got {}", stride));
    }
    if (v.mode != Mode::Attributes && stride != 2 && stride != 4) {
        fail(file, element + ".byteStride", fmt::format("indices are 2 or 4 bytes, got {}", stride));
    }
    if (v.mode == Mode::Triangles && v.count % 3 != 0) {
        fail(file, element + ".count", fmt::format("TRIANGLES take a multiple of 3, got {}", v.count));
    }
    if (v.mode != Mode::Attributes && v.filter != Filter::None) fail(file, element + ".filter", "only ATTRIBUTES are filtered");
    if (v.filter == Filter::Octahedral && stride != 4 && stride != 8) {
        fail(file, element + ".byteStride", fmt::format("OCTAHEDRAL takes 4 or 8, got {}", stride));
    }
    if (v.filter == Filter::Quaternion && stride != 8) {
        fail(file, element + ".byteStride", fmt::format("QUATERNION takes 8, got {}", stride));
    }
    const auto parent_stride = parent.find("byteStride");
    if (parent_stride != parent.end() && !(parent_stride->is_number_unsigned() && *parent_stride == stride)) {
        fail(file, element + ".byteStride", fmt::format("{} differs from the bufferView's byteStride {}", stride,
                                                        parent_stride->dump()));
    }
    if (v.count > std::numeric_limits<std::size_t>::max() / 2 / stride) fail(file, element + ".count", "too large");
    const std::size_t decoded = v.count * stride;
    const auto parent_length = parent.find("byteLength");
    if (parent_length == parent.end() || !(parent_length->is_number_unsigned() && *parent_length == decoded)) {
        fail(file, element, fmt::format("{} elements of {} bytes do not fill the bufferView's byteLength {}", v.count,
                                        stride, parent_length == parent.end() ? "(none)" : parent_length->dump()));
    }
    if (decoded / kMaxExpansion > v.byte_length) {
        fail(file, element, fmt::format("{} bytes cannot decode to {} elements of {} bytes", v.byte_length, v.count,
                                        stride));
    }
}

// Whether buffers[i] of `root` is a fallback buffer: marked so, or holding no
// data (no URI, and not a .glb's binary chunk) while compressed views refer to it.
bool is_fallback(const nlohmann::json& buffer, std::size_t i, bool binary, bool referred) {
    if (!buffer.is_object()) return false;
    const auto ext = buffer.find("extensions");
    if (ext != buffer.end() && ext->is_object()) {
        const auto own = ext->find(kName);
        if (own != ext->end() && own->is_object()) {
            const auto fallback = own->find("fallback");
            if (fallback != own->end() && *fallback == true) return true;
        }
    }
    return referred && !buffer.contains("uri") && (!binary || i > 0);
}

// The decoded bytes of one view, filters applied.
std::vector<unsigned char> decode(const MeshoptView& v, const unsigned char* data, const std::string& element,
                                  const std::string& file) {
    std::vector<unsigned char> out(v.count * v.byte_stride);
    int status = 0;
    switch (v.mode) {
        case MeshoptView::Mode::Attributes:
            status = meshopt_decodeVertexBuffer(out.data(), v.count, v.byte_stride, data, v.byte_length);
            break;
        case MeshoptView::Mode::Triangles:
            status = meshopt_decodeIndexBuffer(out.data(), v.count, v.byte_stride, data, v.byte_length);
            break;
        case MeshoptView::Mode::Indices:
            status = meshopt_decodeIndexSequence(out.data(), v.count, v.byte_stride, data, v.byte_length);
            break;
    }
    if (status != 0) {
        fail(file, element, fmt::format("the compressed data cannot be decoded (libmeshoptimizer's error {})", status));
    }
    switch (v.filter) {
        case MeshoptView::Filter::None: break;
        case MeshoptView::Filter::Octahedral: meshopt_decodeFilterOct(out.data(), v.count, v.byte_stride); break;
        case MeshoptView::Filter::Quaternion: meshopt_decodeFilterQuat(out.data(), v.count, v.byte_stride); break;
        case MeshoptView::Filter::Exponential: meshopt_decodeFilterExp(out.data(), v.count, v.byte_stride); break;
    }
    return out;
}

}  // namespace

MeshoptViews take_meshopt_views(nlohmann::json& root, bool binary, const std::string& file) {
    MeshoptViews out;
    const auto views = root.find("bufferViews");
    if (views == root.end() || !views->is_array()) return out;
    std::vector<bool> referred;
    for (std::size_t i = 0; i < views->size(); ++i) {
        const nlohmann::json& parent = (*views)[i];
        if (!parent.is_object() || !parent.contains("extensions") || !parent["extensions"].is_object()) continue;
        const auto it = parent["extensions"].find(kName);
        if (it == parent["extensions"].end()) continue;
        const Node ext{*it, fmt::format("bufferViews[{}].extensions.{}", i, kName)};
        if (!ext.json.is_object()) fail(file, ext.element, "expected an object");
        MeshoptView v;
        v.view = i;
        v.buffer = *count_member(ext, "buffer", true, file);
        v.byte_offset = count_member(ext, "byteOffset", false, file).value_or(0);
        v.byte_length = *count_member(ext, "byteLength", true, file);
        v.byte_stride = *count_member(ext, "byteStride", true, file);
        v.count = *count_member(ext, "count", true, file);
        v.mode = read_mode(ext, file);
        v.filter = read_filter(ext, file);
        check_layout(v, parent, ext.element, file);
        out.views.push_back(v);
        if (const auto b = parent.find("buffer"); b != parent.end() && b->is_number_unsigned()) {
            const auto index = b->get<std::uint64_t>();
            if (index < 1u << 20) {
                if (referred.size() <= index) referred.resize(index + 1, false);
                referred[index] = true;
            }
        }
    }
    const auto buffers = root.find("buffers");
    if (buffers == root.end() || !buffers->is_array()) return out;
    for (std::size_t i = 0; i < buffers->size(); ++i) {
        nlohmann::json& buffer = (*buffers)[i];
        if (!is_fallback(buffer, i, binary, i < referred.size() && referred[i])) continue;
        buffer = nlohmann::json{{"byteLength", 1}, {"uri", kPlaceholderUri}};
        out.placeholders.push_back(i);
    }
    return out;
}

void decode_meshopt(tinygltf::Model& model, const MeshoptViews& views, const std::string& file) {
    for (std::size_t i : views.placeholders) {
        if (i < model.buffers.size()) model.buffers[i].data.clear();
    }
    for (const MeshoptView& v : views.views) {
        const std::string element = fmt::format("bufferViews[{}].extensions.{}", v.view, kName);
        if (v.buffer >= model.buffers.size()) {
            fail(file, element + ".buffer", fmt::format("buffer {} does not exist (the file has {})", v.buffer,
                                                        model.buffers.size()));
        }
        if (std::find(views.placeholders.begin(), views.placeholders.end(), v.buffer) != views.placeholders.end()) {
            fail(file, element + ".buffer", fmt::format("buffers[{}] is a fallback buffer, which holds no data", v.buffer));
        }
        const std::vector<unsigned char>& source = model.buffers[v.buffer].data;
        if (v.byte_offset > source.size() || v.byte_length > source.size() - v.byte_offset) {
            fail(file, element, fmt::format("bytes {} to {} lie beyond buffers[{}], which holds {}", v.byte_offset,
                                            v.byte_offset + v.byte_length, v.buffer, source.size()));
        }
        if (v.view >= model.bufferViews.size()) fail(file, element, "the bufferView was not read");
        std::vector<unsigned char> decoded = decode(v, source.data() + v.byte_offset, element, file);
        tinygltf::BufferView& view = model.bufferViews[v.view];
        view.buffer = static_cast<int>(model.buffers.size());
        view.byteOffset = 0;
        view.byteLength = decoded.size();
        tinygltf::Buffer buffer;
        buffer.name = element;
        buffer.data = std::move(decoded);
        model.buffers.push_back(std::move(buffer));
    }
}

}  // namespace vkrt::gltf
