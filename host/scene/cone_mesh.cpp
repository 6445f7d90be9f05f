#include "scene/cone_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "scene/vec_math.hpp"

namespace vkrt {

std::uint32_t cone_segments(const dvec3& base, double r0, const dvec3& apex, double r1, const Camera& camera) {
    const dvec3 along = apex - base;
    const double s = std::clamp(glm::dot(camera.eye - base, along) / glm::dot(along, along), 0.0, 1.0);
    const double r = std::max(r0, r1);
    const double distance = std::max(glm::length(camera.eye - (base + s * along)) - r, 0.0);
    // The height of a pixel at that distance (square pixels, vertical field of view).
    const double pixel = distance * 2.0 * std::tan(camera.fov * std::numbers::pi / 360.0) / camera.height;
    std::uint32_t n = kMinConeSegments;
    while (n < kMaxConeSegments && r * (1.0 - std::cos(std::numbers::pi / n)) > kConeSilhouettePixels * pixel) ++n;
    return n;
}

std::vector<Triangle> tessellate_cone(const dvec3& base, double r0, const dvec3& apex, double r1,
                                      std::uint32_t material, std::uint32_t segments) {
    const dvec3 along = apex - base;
    const double length = glm::length(along);
    const dvec3 axis = robust_normalize(along);
    // u, v, axis: a right-handed orthonormal frame, u built from the coordinate axis
    // least aligned with the cone's so that the cross product is well conditioned.
    const dvec3 helper = std::abs(axis.x) <= std::abs(axis.y) && std::abs(axis.x) <= std::abs(axis.z) ? dvec3(1, 0, 0)
                         : std::abs(axis.y) <= std::abs(axis.z)                                      ? dvec3(0, 1, 0)
                                                                                                      : dvec3(0, 0, 1);
    const dvec3 u = glm::normalize(glm::cross(helper, axis));
    const dvec3 v = glm::cross(axis, u);
    auto radial = [&](double angle) { return std::cos(angle) * u + std::sin(angle) * v; };
    // Along the side, the surface rises by `length` while its radius changes by
    // r1 - r0; the normal (length * radial - (r1 - r0) * axis) is perpendicular to
    // both that slope and the circle's tangent.
    auto normal = [&](double angle) { return glm::normalize(length * radial(angle) - (r1 - r0) * axis); };

    std::vector<Triangle> out;
    out.reserve(std::size_t(segments) * 2);
    const double step = 2.0 * std::numbers::pi / segments;
    for (std::uint32_t k = 0; k < segments; ++k) {
        // The last side closes on angle 0 exactly, so neighbouring sides share vertices.
        const double a0 = step * k;
        const double a1 = k + 1 == segments ? 0.0 : step * (k + 1);
        const double mid = step * (k + 0.5);
        const dvec3 b0 = base + r0 * radial(a0), b1 = base + r0 * radial(a1);
        const dvec3 t0 = apex + r1 * radial(a0), t1 = apex + r1 * radial(a1);
        const dvec3 nb0 = r0 > 0.0 ? normal(a0) : normal(mid), nb1 = r0 > 0.0 ? normal(a1) : normal(mid);
        const dvec3 nt0 = r1 > 0.0 ? normal(a0) : normal(mid), nt1 = r1 > 0.0 ? normal(a1) : normal(mid);
        // The quad b0, b1, t1, t0 turns counter-clockwise seen from outside.
        if (r0 > 0.0) out.push_back(Triangle{{b0, b1, t1}, std::array{nb0, nb1, nt1}, material});
        if (r1 > 0.0) out.push_back(Triangle{{b0, t1, t0}, std::array{nb0, nt1, nt0}, material});
    }
    return out;
}

}  // namespace vkrt
