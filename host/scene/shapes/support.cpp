#include "scene/shapes/support.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/geometric.hpp>

namespace vkrt {

kernel::vec4 to_vec4(const glm::dvec3& v, double w) {
    return kernel::vec4(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z),
                        static_cast<float>(w));
}

glm::dvec3 to_dvec3(const kernel::vec4& v) { return glm::dvec3(v.x, v.y, v.z); }

void require_finite(std::initializer_list<kernel::vec4> values, const char* kind) {
    for (const kernel::vec4& v : values) {
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w)) {
            throw std::invalid_argument(fmt::format("grid: a {} has a non-finite coordinate", kind));
        }
    }
}

Aabb finite_or_throw(const Aabb& box, const char* kind) {
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a])) {
            throw std::invalid_argument(fmt::format("grid: a {} has a non-finite coordinate", kind));
        }
    }
    return box;
}

glm::dvec3 disc_extent(const glm::dvec3& normal, double radius) {
    const double len2 = glm::dot(normal, normal);
    if (!(len2 > 0.0)) return glm::dvec3(radius);
    glm::dvec3 e;
    for (int a = 0; a < 3; ++a) e[a] = radius * std::sqrt(std::max(0.0, 1.0 - normal[a] * normal[a] / len2));
    return e;
}

}  // namespace vkrt
