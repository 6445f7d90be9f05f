#pragma once
// The triangle's host half (its kernel half: shaders/kernel/shapes/triangle.glsl),
// the parallelogram's too, which shares its record: the scene's record, the JSON
// object that gives one, and its kernel record, emitter and box. The functions every
// kind's host half declares are listed in shaders/kernel/shapes/kinds.glsl.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "scene/shapes/shape_reader.hpp"
#include "scene/shapes/support.hpp"

namespace vkrt {

// A triangle v0 v1 v2, or with `parallelogram` the parallelogram v0, v1, v2,
// v0 + v2 - v1: a scene file's quad, one primitive. The front face is the side of
// cross(v1 - v0, v2 - v0).
struct Triangle {
    std::array<glm::dvec3, 3> vertices{};
    std::optional<std::array<glm::dvec3, 3>> normals;  // interpolated when present (triangles only)
    std::uint32_t material = 0;
    bool parallelogram = false;
    // Texture coordinates of the three vertices; without them a triangle has (0, 0),
    // (1, 0), (0, 1) and a parallelogram (0, 0), (1, 0), (1, 1): its corners.
    std::optional<std::array<glm::dvec2, 3>> uvs{};
    // Second texture coordinates of the three vertices, which the textures on its
    // material's second mapping read where that mapping has coordinates of its own
    // (Material::SecondMapping); without them such a triangle reads its first ones.
    std::optional<std::array<glm::dvec2, 3>> second_uvs{};
    // Linear RGBA colours of the three vertices (glTF's COLOR_0), each in [0, 1]:
    // they multiply the material's colour and opacity (kernel/vertex_data.glsl).
    std::optional<std::array<glm::vec4, 3>> colors{};
    // Unit tangents of the three vertices along +u, w = +-1 the sign of the bitangent
    // cross(n, t) w (glTF's TANGENT): a normal map's frame (kernel/normal_map.glsl).
    std::optional<std::array<glm::vec4, 3>> tangents{};
};

// The quad corner, corner + e1, corner + e1 + e2, corner + e2, facing cross(e1, e2):
// what the scene file's "quad" is.
inline Triangle quad(glm::dvec3 corner, glm::dvec3 e1, glm::dvec3 e2, std::uint32_t material) {
    return Triangle{{corner, corner + e1, corner + e1 + e2}, std::nullopt, material, true};
}

// A triangle's texture coordinates at v0, v1, v2: its own, or those of the unit
// square's corners.
std::array<glm::dvec2, 3> texture_corners(const Triangle& t);

// {"type": "triangle", "vertices", "normals", "material"} (docs/scene-format.md).
// One of zero area is dropped, and a zero normal replaced by the face normal; both
// are counted in `reader` for a warning.
void read_shape(const json::Node& object, ShapeReader& reader, std::vector<Triangle>& out);
kernel::Triangle flatten(const Triangle& t, const glm::dvec3& origin);
std::uint32_t emitter_parts(const Triangle& t);
double emitter_area(const Triangle& t, std::uint32_t part);
// A parallelogram's fourth vertex as the kernel computes it, in float.
Aabb bounds(const kernel::Triangle& t);

}  // namespace vkrt
