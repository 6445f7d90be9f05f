#include "scene/gltf_accessor.hpp"

#include <cmath>
#include <cstring>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/vec4.hpp>
#include <tiny_gltf.h>

#include "scene/scene_error.hpp"

namespace vkrt::gltf {
namespace {

[[noreturn]] void fail(const Origin& origin, const std::string& what) {
    throw SceneError(fmt::format("{}: {}: {}", origin.file, origin.element, what));
}

std::size_t component_size(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

const char* component_name(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        default: return "an unknown component type";
    }
}

// The bytes of an accessor's elements: element i starts at data + i * stride and
// holds `components` values of `size` bytes each.
struct Elements {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
    std::size_t size = 0;
    int component = 0;
    bool normalized = false;
};

Elements locate(const tinygltf::Model& model, int index, int type, const char* type_name, const Origin& origin) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        fail(origin, fmt::format("accessor {} does not exist (the file has {})", index, model.accessors.size()));
    }
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    const std::string name = fmt::format("accessors[{}]", index);
    if (a.type != type) fail(origin, fmt::format("{} is not {}", name, type_name));
    if (a.sparse.isSparse) fail(origin, fmt::format("{} is sparse, which vkrt does not read yet", name));
    Elements e;
    e.component = a.componentType;
    e.size = component_size(a.componentType);
    e.count = a.count;
    e.normalized = a.normalized;
    if (e.size == 0) fail(origin, fmt::format("{} has component type {}, which glTF does not define", name, a.componentType));
    const std::size_t components = type == TINYGLTF_TYPE_VEC4   ? 4
                                   : type == TINYGLTF_TYPE_VEC3 ? 3
                                   : type == TINYGLTF_TYPE_VEC2 ? 2
                                                                : 1;
    const std::size_t element = e.size * components;
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size()) {
        fail(origin, fmt::format("{} refers to bufferView {}, which does not exist (the file has {})", name,
                                 a.bufferView, model.bufferViews.size()));
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
        fail(origin, fmt::format("bufferViews[{}] refers to buffer {}, which does not exist", a.bufferView, view.buffer));
    }
    const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
        fail(origin, fmt::format("bufferViews[{}] spans bytes {} to {} of buffers[{}], which holds {}", a.bufferView,
                                 view.byteOffset, view.byteOffset + view.byteLength, view.buffer, buffer.size()));
    }
    e.stride = view.byteStride == 0 ? element : view.byteStride;
    if (e.stride < element) {
        fail(origin, fmt::format("bufferViews[{}] has a byteStride of {}, less than an element of {} ({} bytes)",
                                 a.bufferView, view.byteStride, name, element));
    }
    // The last element ends at byteOffset + (count - 1) * stride + element; counted
    // in a way that cannot overflow for any count a file can claim.
    if (e.count > 0) {
        const std::size_t room = view.byteLength;
        const bool fits = a.byteOffset <= room && element <= room - a.byteOffset &&
                          (e.count - 1) <= (room - a.byteOffset - element) / e.stride;
        if (!fits) {
            fail(origin, fmt::format("{} ({} elements of {} bytes, from byte {}) does not fit in bufferViews[{}] of "
                                     "{} bytes",
                                     name, e.count, element, a.byteOffset, a.bufferView, room));
        }
    }
    e.data = buffer.data() + view.byteOffset + a.byteOffset;
    return e;
}

template <typename T>
T load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);  // glTF data is little-endian, as is every host vkrt builds for
    return v;
}

// Component k of element i as a double: floats as they are, normalized integers
// mapped to [0, 1] or [-1, 1] as the specification says (3.11), other integers as
// their values (KHR_mesh_quantization).
double component_value(const Elements& e, std::size_t i, std::size_t k) {
    const unsigned char* p = e.data + i * e.stride + k * e.size;
    const bool n = e.normalized;
    switch (e.component) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
        case TINYGLTF_COMPONENT_TYPE_BYTE: return n ? std::max(load<std::int8_t>(p) / 127.0, -1.0) : load<std::int8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return n ? load<std::uint8_t>(p) / 255.0 : load<std::uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return n ? std::max(load<std::int16_t>(p) / 32767.0, -1.0) : load<std::int16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return n ? load<std::uint16_t>(p) / 65535.0 : load<std::uint16_t>(p);
        default: return 0.0;
    }
}

}  // namespace

namespace {

// An accessor of `N` floats (or integers, as `integers` allows) per element, each finite.
template <int N, typename Vec>
std::vector<Vec> read_floats(const tinygltf::Model& model, int accessor, int type, const char* name,
                             const Origin& origin, Integers integers) {
    const Elements e = locate(model, accessor, type, name, origin);
    const bool short_integer = e.size < 4;  // BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT
    if (e.component != TINYGLTF_COMPONENT_TYPE_FLOAT && !e.normalized &&
        !(short_integer && integers == Integers::Quantized)) {
        fail(origin, fmt::format("accessors[{}] holds {} values that are not normalized; expected FLOAT or normalized "
                                 "integers{}",
                                 accessor, component_name(e.component),
                                 short_integer && integers == Integers::Quantizable
                                     ? " (KHR_mesh_quantization allows plain ones, but the file does not use it)"
                                     : ""));
    }
    if (e.normalized && e.component != TINYGLTF_COMPONENT_TYPE_FLOAT && !short_integer) {
        fail(origin, fmt::format("accessors[{}] holds normalized {} values; glTF normalizes bytes and shorts only",
                                 accessor, component_name(e.component)));
    }
    std::vector<Vec> out(e.count);
    for (std::size_t i = 0; i < e.count; ++i) {
        for (int k = 0; k < N; ++k) {
            const double v = component_value(e, i, static_cast<std::size_t>(k));
            if (!std::isfinite(v)) fail(origin, fmt::format("accessors[{}] element {} is not finite", accessor, i));
            out[i][k] = v;
        }
    }
    return out;
}

}  // namespace

std::vector<glm::dvec3> read_vec3(const tinygltf::Model& model, int accessor, const Origin& origin,
                                  Integers integers) {
    return read_floats<3, glm::dvec3>(model, accessor, TINYGLTF_TYPE_VEC3, "a VEC3", origin, integers);
}

std::vector<glm::dvec2> read_vec2(const tinygltf::Model& model, int accessor, const Origin& origin,
                                  Integers integers) {
    return read_floats<2, glm::dvec2>(model, accessor, TINYGLTF_TYPE_VEC2, "a VEC2", origin, integers);
}

std::vector<glm::dvec4> read_vec4(const tinygltf::Model& model, int accessor, const Origin& origin,
                                  Integers integers) {
    return read_floats<4, glm::dvec4>(model, accessor, TINYGLTF_TYPE_VEC4, "a VEC4", origin, integers);
}

std::vector<glm::vec4> read_colors(const tinygltf::Model& model, int accessor, const Origin& origin) {
    const bool rgba = accessor >= 0 && std::size_t(accessor) < model.accessors.size() &&
                      model.accessors[std::size_t(accessor)].type == TINYGLTF_TYPE_VEC4;
    std::vector<glm::dvec4> read;
    if (rgba) {
        read = read_floats<4, glm::dvec4>(model, accessor, TINYGLTF_TYPE_VEC4, "a VEC3 or VEC4", origin,
                                          Integers::Normalized);
    } else {
        for (const glm::dvec3& c : read_floats<3, glm::dvec3>(model, accessor, TINYGLTF_TYPE_VEC3, "a VEC3 or VEC4",
                                                              origin, Integers::Normalized)) {
            read.emplace_back(c, 1.0);
        }
    }
    std::vector<glm::vec4> out(read.size());
    for (std::size_t i = 0; i < read.size(); ++i) out[i] = glm::vec4(glm::clamp(read[i], 0.0, 1.0));
    return out;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor, std::uint32_t limit,
                                        const Origin& origin) {
    const Elements e = locate(model, accessor, TINYGLTF_TYPE_SCALAR, "a SCALAR", origin);
    if (e.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && e.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        e.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        fail(origin, fmt::format("accessors[{}] holds {}; indices are UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
                                 accessor, component_name(e.component)));
    }
    std::vector<std::uint32_t> out(e.count);
    for (std::size_t i = 0; i < e.count; ++i) {
        const unsigned char* p = e.data + i * e.stride;
        const std::uint32_t v = e.size == 1 ? load<std::uint8_t>(p)
                                : e.size == 2 ? load<std::uint16_t>(p)
                                              : load<std::uint32_t>(p);
        if (v >= limit) {
            fail(origin, fmt::format("index {} (element {} of accessors[{}]) is out of range: the primitive has {} "
                                     "vertices",
                                     v, i, accessor, limit));
        }
        out[i] = v;
    }
    return out;
}

}  // namespace vkrt::gltf
