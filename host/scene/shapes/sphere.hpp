#pragma once
// The sphere's host half (its kernel half: shaders/kernel/shapes/sphere.glsl): the
// scene's record, the JSON object that gives one, and its kernel record, emitter
// and box. The functions every kind's host half declares are listed in
// shaders/kernel/shapes/kinds.glsl.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/shapes/shape_reader.hpp"
#include "scene/shapes/support.hpp"

namespace vkrt {

struct Sphere {
    glm::dvec3 center{0.0};
    double radius = 1.0;
    std::uint32_t material = 0;  // index into Scene::materials
};

// {"type": "sphere", "center", "radius", "material"} (docs/scene-format.md).
void read_shape(const json::Node& object, ShapeReader& reader, std::vector<Sphere>& out);
kernel::Sphere flatten(const Sphere& s, const glm::dvec3& origin);
std::uint32_t emitter_parts(const Sphere& s);
double emitter_area(const Sphere& s, std::uint32_t part);
Aabb bounds(const kernel::Sphere& s);

}  // namespace vkrt
