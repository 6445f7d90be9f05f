#include "scene/shapes/ring.hpp"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>

#include "scene/vec_math.hpp"

namespace vkrt {

void read_shape(const json::Node& n, ShapeReader& reader, std::vector<Ring>& out) {
    n.allow_only({"center", "normal", "inner", "outer", "material", "type"});
    Ring r;
    r.center = n.required("center").vec3();
    const json::Node normal = n.required("normal");
    r.normal = normal.vec3();
    if (!is_nonzero(r.normal)) normal.fail("expected a non-zero vector, got [0, 0, 0]");
    // Normalized here: the kernel's ring test and bounds take it as unit length.
    r.normal = robust_normalize(r.normal);
    if (auto inner = n.find("inner")) r.inner = inner->number_at_least(0.0);
    r.outer = n.required("outer").number_above(0.0);
    if (!(r.inner < r.outer)) {
        n.fail_field("inner", fmt::format("expected inner < outer, got inner {} and outer {}", r.inner, r.outer));
    }
    r.material = reader.material_of(n);
    out.push_back(r);
}

kernel::Ring flatten(const Ring& r, const glm::dvec3& origin) {
    return kernel::Ring(to_vec4(r.center - origin, r.inner), to_vec4(r.normal, r.outer),
                        kernel::uvec4(r.material, 0u, 0u, 0u));
}

std::uint32_t emitter_parts(const Ring&) { return 1; }

double emitter_area(const Ring& r, std::uint32_t) {
    return glm::pi<double>() * (r.outer * r.outer - r.inner * r.inner);
}

Aabb bounds(const kernel::Ring& r) {
    require_finite({r.center_inner, r.normal_outer}, "ring");
    const glm::dvec3 c = to_dvec3(r.center_inner);
    const glm::dvec3 e = disc_extent(to_dvec3(r.normal_outer), r.normal_outer.w);
    return finite_or_throw({c - e, c + e}, "ring");
}

}  // namespace vkrt
