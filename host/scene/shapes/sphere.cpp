#include "scene/shapes/sphere.hpp"

#include <glm/gtc/constants.hpp>

namespace vkrt {

void read_shape(const json::Node& n, ShapeReader& reader, std::vector<Sphere>& out) {
    n.allow_only({"center", "radius", "material", "type"});
    Sphere s;
    s.center = n.required("center").vec3();
    s.radius = n.required("radius").number_above(0.0);
    s.material = reader.material_of(n);
    out.push_back(s);
}

kernel::Sphere flatten(const Sphere& s, const glm::dvec3& origin) {
    return kernel::Sphere(to_vec4(s.center - origin, s.radius), kernel::uvec4(s.material, 0u, 0u, 0u));
}

std::uint32_t emitter_parts(const Sphere&) { return 1; }

double emitter_area(const Sphere& s, std::uint32_t) { return 4.0 * glm::pi<double>() * s.radius * s.radius; }

Aabb bounds(const kernel::Sphere& s) {
    const glm::dvec3 c = to_dvec3(s.center_radius);
    const double r = s.center_radius.w;
    return finite_or_throw({c - r, c + r}, "sphere");
}

}  // namespace vkrt
