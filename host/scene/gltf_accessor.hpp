#pragma once
// Reading a glTF 2.0 accessor's elements (glTF 2.0 specification, section 3.6),
// with every index and byte range checked against what the file holds: a bad file
// ends in a SceneError naming the file and the element that asked for the data,
// never in a read out of bounds.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace tinygltf {
class Model;
}

namespace vkrt::gltf {

// Where a read comes from, for messages: "<file>: <element>: ...".
struct Origin {
    std::string file;
    std::string element;  // e.g. "meshes[2].primitives[0].attributes.POSITION"
};

// Which integers an attribute may hold besides floats.
enum class Integers {
    Normalized,   // bytes and shorts normalized to [0, 1] or [-1, 1] (glTF 2.0, 3.7.2.1)
    Quantizable,  // the same; the message for plain ones names KHR_mesh_quantization, not used by the file
    Quantized,    // also plain bytes and shorts, taken as their values (KHR_mesh_quantization)
};

// A VEC3 accessor of floats (or integers, as `integers` allows) as doubles; each
// value finite.
std::vector<glm::dvec3> read_vec3(const tinygltf::Model& model, int accessor, const Origin& origin,
                                  Integers integers = Integers::Normalized);

// A VEC2 accessor, as read_vec3 (texture coordinates).
std::vector<glm::dvec2> read_vec2(const tinygltf::Model& model, int accessor, const Origin& origin,
                                  Integers integers = Integers::Normalized);

// A VEC4 accessor, as read_vec3 (tangents).
std::vector<glm::dvec4> read_vec4(const tinygltf::Model& model, int accessor, const Origin& origin,
                                  Integers integers = Integers::Normalized);

// A COLOR_0 accessor: VEC3 (alpha 1) or VEC4, of floats or normalized unsigned bytes or
// shorts, each component clamped into [0, 1].
std::vector<glm::vec4> read_colors(const tinygltf::Model& model, int accessor, const Origin& origin);

// A SCALAR accessor of unsigned bytes, shorts or ints, each below `limit`.
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor, std::uint32_t limit,
                                        const Origin& origin);

}  // namespace vkrt::gltf
