#include "accel/box_overlap.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace vkrt {

PolygonOverlap::PolygonOverlap(std::span<const glm::dvec3> v) {
    const std::size_t n = std::min(v.size(), kMaxVertices);
    lo_ = glm::dvec3(1.0);
    hi_ = glm::dvec3(-1.0);   // empty: overlaps nothing
    if (n == 0) return;
    lo_ = hi_ = v[0];
    for (std::size_t i = 1; i < n; ++i) {
        lo_ = glm::min(lo_, v[i]);
        hi_ = glm::max(hi_, v[i]);
    }
    auto add = [&](const glm::dvec3& axis) {
        if (axis == glm::dvec3(0.0)) return;
        double lo = glm::dot(v[0], axis), hi = lo;
        for (std::size_t i = 1; i < n; ++i) {
            const double p = glm::dot(v[i], axis);
            lo = std::min(lo, p);
            hi = std::max(hi, p);
        }
        axis_[axes_] = axis;
        min_[axes_] = lo;
        max_[axes_] = hi;
        ++axes_;
    };
    // The plane's normal, from the two edges at the first vertex.
    if (n >= 3) add(glm::cross(v[1] - v[0], v[n - 1] - v[0]));
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 edge = v[(i + 1) % n] - v[i];
        add({0.0, -edge.z, edge.y});   // edge x (1, 0, 0)
        add({edge.z, 0.0, -edge.x});   // edge x (0, 1, 0)
        add({-edge.y, edge.x, 0.0});   // edge x (0, 0, 1)
    }
}

bool PolygonOverlap::overlaps(const glm::dvec3& lo, const glm::dvec3& hi) const {
    // The box axes: the two boxes.
    if (glm::any(glm::greaterThan(lo_, hi)) || glm::any(glm::lessThan(hi_, lo))) return false;
    const glm::dvec3 centre = (lo + hi) * 0.5, half = (hi - lo) * 0.5;
    for (std::size_t k = 0; k < axes_; ++k) {
        const glm::dvec3& a = axis_[k];
        const double c = glm::dot(centre, a);
        const double r = half.x * std::abs(a.x) + half.y * std::abs(a.y) + half.z * std::abs(a.z);
        if (min_[k] > c + r || max_[k] < c - r) return false;
    }
    return true;
}

}  // namespace vkrt
