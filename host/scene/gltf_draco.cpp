#include "scene/gltf_draco.hpp"

#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene/scene_error.hpp"

namespace vkrt::gltf {
namespace {

constexpr const char* kName = "KHR_draco_mesh_compression";

[[noreturn]] void fail(const std::string& file, const std::string& element, const std::string& what) {
    throw SceneError(fmt::format("{}: {}: {}", file, element, what));
}

int index_member(const nlohmann::json& object, const char* key, const std::string& element, const std::string& file) {
    const auto it = object.find(key);
    if (it == object.end()) fail(file, element, fmt::format("no {}", key));
    if (!it->is_number_unsigned() || it->get<std::uint64_t>() > std::uint64_t(std::numeric_limits<int>::max())) {
        fail(file, element + "." + key, "expected an index");
    }
    return it->get<int>();
}

DracoPrimitive read_extension(const nlohmann::json& ext, const std::string& element, const std::string& file) {
    if (!ext.is_object()) fail(file, element, "expected an object");
    DracoPrimitive p;
    p.buffer_view = index_member(ext, "bufferView", element, file);
    const auto attributes = ext.find("attributes");
    if (attributes == ext.end() || !attributes->is_object()) fail(file, element + ".attributes", "expected an object");
    for (const auto& [name, id] : attributes->items()) {
        p.attributes.emplace_back(name, index_member(*attributes, name.c_str(), element + ".attributes", file));
    }
    return p;
}

// The decoded mesh of a primitive's stream.
std::unique_ptr<draco::Mesh> decode_stream(const tinygltf::Model& model, int view_index, const std::string& element,
                                           const std::string& file) {
    if (static_cast<std::size_t>(view_index) >= model.bufferViews.size()) {
        fail(file, element + ".bufferView",
             fmt::format("bufferView {} does not exist (the file has {})", view_index, model.bufferViews.size()));
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(view_index)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
        fail(file, element, fmt::format("bufferViews[{}] refers to buffer {}, which does not exist", view_index, view.buffer));
    }
    const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
        fail(file, element, fmt::format("bufferViews[{}] spans bytes {} to {} of buffers[{}], which holds {}", view_index,
                                        view.byteOffset, view.byteOffset + view.byteLength, view.buffer, buffer.size()));
    }
    const char* data = reinterpret_cast<const char*>(buffer.data() + view.byteOffset);
    const std::string what = fmt::format("the Draco stream in bufferViews[{}]", view_index);
    draco::DecoderBuffer probe;
    probe.Init(data, view.byteLength);
    const auto type = draco::Decoder::GetEncodedGeometryType(&probe);
    if (!type.ok()) {
        fail(file, element, fmt::format("{} cannot be decoded: {}", what, one_line(type.status().error_msg_string())));
    }
    if (type.value() != draco::TRIANGULAR_MESH) fail(file, element, fmt::format("{} holds no triangle mesh", what));
    draco::DecoderBuffer stream;
    stream.Init(data, view.byteLength);
    draco::Decoder decoder;
    auto mesh = decoder.DecodeMeshFromBuffer(&stream);
    if (!mesh.ok()) {
        fail(file, element, fmt::format("{} cannot be decoded: {}", what, one_line(mesh.status().error_msg_string())));
    }
    return std::move(mesh).value();
}

std::size_t components(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;
    }
}

// Point i's value of `attribute` as `n` values of T, appended to `out`.
template <typename T>
bool append_point(const draco::PointAttribute& attribute, draco::PointIndex::ValueType i, std::size_t n,
                  std::vector<unsigned char>& out) {
    if (!attribute.is_mapping_identity() && i >= attribute.indices_map_size()) return false;
    const draco::AttributeValueIndex value = attribute.mapped_index(draco::PointIndex(i));
    if (value.value() >= attribute.size()) return false;
    T v[4] = {};
    if (!attribute.ConvertValue<T>(value, static_cast<std::int8_t>(n), v)) return false;
    const std::size_t at = out.size();
    out.resize(at + n * sizeof(T));
    std::memcpy(out.data() + at, v, n * sizeof(T));
    return true;
}

bool append_point(const draco::PointAttribute& attribute, draco::PointIndex::ValueType i, std::size_t n, int type,
                  std::vector<unsigned char>& out) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return append_point<std::int8_t>(attribute, i, n, out);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return append_point<std::uint8_t>(attribute, i, n, out);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return append_point<std::int16_t>(attribute, i, n, out);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return append_point<std::uint16_t>(attribute, i, n, out);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return append_point<std::uint32_t>(attribute, i, n, out);
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return append_point<float>(attribute, i, n, out);
        default: return false;
    }
}

// A new accessor like `like` over `bytes`, in a buffer and view of its own; its index.
int add_accessor(tinygltf::Model& model, tinygltf::Accessor like, std::vector<unsigned char> bytes,
                 const std::string& name) {
    tinygltf::Buffer buffer;
    buffer.name = name;
    buffer.data = std::move(bytes);
    tinygltf::BufferView view;
    view.buffer = static_cast<int>(model.buffers.size());
    view.byteLength = buffer.data.size();
    model.buffers.push_back(std::move(buffer));
    like.bufferView = static_cast<int>(model.bufferViews.size());
    like.byteOffset = 0;
    like.sparse.isSparse = false;
    model.bufferViews.push_back(std::move(view));
    model.accessors.push_back(std::move(like));
    return static_cast<int>(model.accessors.size() - 1);
}

void decode_primitive(tinygltf::Model& model, const DracoPrimitive& p, const std::string& file) {
    const std::string at = fmt::format("meshes[{}].primitives[{}]", p.mesh, p.primitive);
    const std::string element = at + ".extensions." + kName;
    if (p.mesh >= model.meshes.size() || p.primitive >= model.meshes[p.mesh].primitives.size()) {
        fail(file, element, "the primitive was not read");
    }
    const std::unique_ptr<draco::Mesh> mesh = decode_stream(model, p.buffer_view, element, file);
    const draco::PointIndex::ValueType points = mesh->num_points();
    std::vector<std::pair<std::string, int>> decoded;  // attribute -> its new accessor
    for (const auto& [name, id] : p.attributes) {
        const std::string where = element + ".attributes." + name;
        const tinygltf::Primitive& prim = model.meshes[p.mesh].primitives[p.primitive];
        const auto accessor = prim.attributes.find(name);
        if (accessor == prim.attributes.end()) fail(file, where, fmt::format("the primitive has no {} attribute", name));
        if (accessor->second < 0 || static_cast<std::size_t>(accessor->second) >= model.accessors.size()) {
            fail(file, at + ".attributes." + name,
                 fmt::format("accessor {} does not exist (the file has {})", accessor->second, model.accessors.size()));
        }
        const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(accessor->second)];
        const std::string name_a = fmt::format("accessors[{}]", accessor->second);
        const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
        if (attribute == nullptr) fail(file, where, fmt::format("the Draco stream has no attribute of id {}", id));
        const std::size_t n = components(a.type);
        if (n == 0 || n != attribute->num_components()) {
            fail(file, where, fmt::format("the Draco attribute has {} components; {} has {}", attribute->num_components(),
                                          name_a, n == 0 ? "a matrix type" : std::to_string(n)));
        }
        if (a.count != points) {
            fail(file, where, fmt::format("the Draco stream holds {} points; {} counts {}", points, name_a, a.count));
        }
        std::vector<unsigned char> bytes;
        for (draco::PointIndex::ValueType i = 0; i < points; ++i) {
            if (!append_point(*attribute, i, n, a.componentType, bytes)) {
                fail(file, where, fmt::format("point {} of the Draco stream has no value that {} can hold", i, name_a));
            }
        }
        decoded.emplace_back(name, add_accessor(model, a, std::move(bytes), where));
    }
    // The faces as UNSIGNED_INT indices; the loader checks each against the vertices.
    tinygltf::Accessor indices;
    if (p.indices >= 0) {
        if (static_cast<std::size_t>(p.indices) >= model.accessors.size()) {
            fail(file, at + ".indices",
                 fmt::format("accessor {} does not exist (the file has {})", p.indices, model.accessors.size()));
        }
        indices = model.accessors[static_cast<std::size_t>(p.indices)];
        if (indices.count != 3 * std::size_t(mesh->num_faces())) {
            fail(file, at + ".indices", fmt::format("the Draco stream holds {} triangles; accessors[{}] counts {} indices",
                                                    mesh->num_faces(), p.indices, indices.count));
        }
    }
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.count = 3 * std::size_t(mesh->num_faces());
    indices.normalized = false;
    std::vector<unsigned char> bytes(indices.count * 4);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
        const draco::Mesh::Face& face = mesh->face(f);
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t v = face[k].value();
            std::memcpy(bytes.data() + (3 * std::size_t(f.value()) + k) * 4, &v, 4);
        }
    }
    const int new_indices = add_accessor(model, indices, std::move(bytes), at + ".indices");
    tinygltf::Primitive& prim = model.meshes[p.mesh].primitives[p.primitive];
    for (const auto& [name, index] : decoded) prim.attributes[name] = index;
    prim.indices = new_indices;
    // A strip decodes to a list of its triangles (the extension allows the two).
    if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) prim.mode = TINYGLTF_MODE_TRIANGLES;
}

}  // namespace

std::vector<DracoPrimitive> take_draco_primitives(nlohmann::json& root, const std::string& file) {
    std::vector<DracoPrimitive> out;
    const auto meshes = root.find("meshes");
    if (meshes == root.end() || !meshes->is_array()) return out;
    for (std::size_t m = 0; m < meshes->size(); ++m) {
        nlohmann::json& mesh = (*meshes)[m];
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        nlohmann::json& primitives = mesh["primitives"];
        for (std::size_t i = 0; i < primitives.size(); ++i) {
            nlohmann::json& prim = primitives[i];
            if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object()) continue;
            const auto ext = prim["extensions"].find(kName);
            if (ext == prim["extensions"].end()) continue;
            const std::string element = fmt::format("meshes[{}].primitives[{}]", m, i);
            DracoPrimitive p = read_extension(*ext, element + ".extensions." + kName, file);
            p.mesh = m;
            p.primitive = i;
            if (prim.contains("indices")) {
                p.indices = index_member(prim, "indices", element, file);
                prim.erase("indices");
            }
            out.push_back(std::move(p));
        }
    }
    return out;
}

void decode_draco(tinygltf::Model& model, const std::vector<DracoPrimitive>& primitives, const std::string& file) {
    for (const DracoPrimitive& p : primitives) decode_primitive(model, p, file);
}

}  // namespace vkrt::gltf
