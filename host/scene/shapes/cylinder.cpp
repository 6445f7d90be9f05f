#include "scene/shapes/cylinder.hpp"

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "scene/vec_math.hpp"

namespace vkrt {

void read_shape(const json::Node& n, ShapeReader& reader, std::vector<Cylinder>& out) {
    n.allow_only({"base", "top", "radius", "capped", "material", "type"});
    Cylinder c;
    c.base = n.required("base").vec3();
    const json::Node top = n.required("top");
    c.top = top.vec3();
    if (!is_nonzero(c.top - c.base)) {
        top.fail(fmt::format("top must differ from base (both are {})", json::format_vec3(c.base)));
    }
    // The kernel gets floats: ends that round to one point would leave no axis.
    const glm::vec3 base_f(c.base), top_f(c.top);
    if (base_f == top_f) {
        top.fail(fmt::format("top {} and base {} round to the same single-precision point, so the cylinder has "
                             "no axis",
                             json::format_vec3(c.top), json::format_vec3(c.base)));
    }
    c.radius = n.required("radius").number_above(0.0);
    if (auto capped = n.find("capped")) c.capped = capped->boolean();
    c.material = reader.material_of(n);
    out.push_back(c);
}

kernel::Cylinder flatten(const Cylinder& c, const glm::dvec3& origin) {
    return kernel::Cylinder(to_vec4(c.base - origin, c.radius), to_vec4(c.top - origin, c.capped ? 1.0 : 0.0),
                            kernel::uvec4(c.material, 0u, 0u, 0u));
}

std::uint32_t emitter_parts(const Cylinder& c) { return c.capped ? 3 : 1; }

double emitter_area(const Cylinder& c, std::uint32_t part) {
    const double pi = glm::pi<double>();
    if (part == kernel::CYLINDER_SIDE) return 2.0 * pi * c.radius * glm::length(c.top - c.base);
    return pi * c.radius * c.radius;  // either cap
}

Aabb bounds(const kernel::Cylinder& cyl) {
    require_finite({cyl.base_radius, cyl.top_capped}, "cylinder");
    const glm::dvec3 b = to_dvec3(cyl.base_radius);
    const glm::dvec3 t = to_dvec3(cyl.top_capped);
    const glm::dvec3 e = disc_extent(t - b, cyl.base_radius.w);
    return finite_or_throw({glm::min(b, t) - e, glm::max(b, t) + e}, "cylinder");
}

}  // namespace vkrt
