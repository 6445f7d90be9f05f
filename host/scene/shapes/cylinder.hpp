#pragma once
// The cylinder's host half (its kernel half: shaders/kernel/shapes/cylinder.glsl):
// the scene's record, the JSON object that gives one, and its kernel record, emitters
// and box. The functions every kind's host half declares are listed in
// shaders/kernel/shapes/kinds.glsl.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/shapes/shape_reader.hpp"
#include "scene/shapes/support.hpp"

namespace vkrt {

// A cylinder of `radius` around the segment base -> top, open or closed by two
// discs (`capped`). Its front face is the outside.
struct Cylinder {
    glm::dvec3 base{0.0};
    glm::dvec3 top{0.0, 1.0, 0.0};  // differs from base
    double radius = 1.0;
    bool capped = false;
    std::uint32_t material = 0;
};

// {"type": "cylinder", "base", "top", "radius", "capped", "material"} (docs/scene-format.md).
void read_shape(const json::Node& object, ShapeReader& reader, std::vector<Cylinder>& out);
kernel::Cylinder flatten(const Cylinder& c, const glm::dvec3& origin);
// Up to three emitters, its side and its caps (kernel::CYLINDER_SIDE, _BASE_CAP,
// _TOP_CAP), so that each is picked by its own power and sampled by its own
// parameterization.
std::uint32_t emitter_parts(const Cylinder& c);
double emitter_area(const Cylinder& c, std::uint32_t part);
// It lies within the convex hull of its two end discs, so its box is theirs.
Aabb bounds(const kernel::Cylinder& c);

}  // namespace vkrt
