#pragma once
// The ring's host half (its kernel half: shaders/kernel/shapes/ring.glsl): the scene's
// record, the JSON object that gives one, and its kernel record, emitter and box.
// The functions every kind's host half declares are listed in
// shaders/kernel/shapes/kinds.glsl.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/shapes/shape_reader.hpp"
#include "scene/shapes/support.hpp"

namespace vkrt {

// An annulus: the points of the plane through `center` perpendicular to `normal`
// whose distance from the centre lies in [inner, outer]; inner 0 is a disc. Its
// front face is the side `normal` points to.
struct Ring {
    glm::dvec3 center{0.0};
    glm::dvec3 normal{0.0, 1.0, 0.0};  // unit length (the loaders normalize it)
    double inner = 0.0;                // 0 <= inner < outer
    double outer = 1.0;
    std::uint32_t material = 0;
};

// {"type": "ring", "center", "normal", "inner", "outer", "material"} (docs/scene-format.md).
void read_shape(const json::Node& object, ShapeReader& reader, std::vector<Ring>& out);
kernel::Ring flatten(const Ring& r, const glm::dvec3& origin);
std::uint32_t emitter_parts(const Ring& r);
double emitter_area(const Ring& r, std::uint32_t part);
// Its outer disc's box.
Aabb bounds(const kernel::Ring& r);

}  // namespace vkrt
