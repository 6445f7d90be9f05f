#pragma once
// Whether a flat convex polygon (a triangle, or a quad's parallelogram) overlaps a
// box: the separating-axis test of Akenine-Möller, "Fast 3D Triangle-Box Overlap
// Testing" (2001), for up to four vertices. The grid bins a triangle only into the
// cells it overlaps, not every cell of its bounding box: a long thin triangle across
// a diagonal touches a few of the many cells its box spans.
#include <array>
#include <cstddef>
#include <span>

#include <glm/vec3.hpp>

namespace vkrt {

// One polygon, set up once to be tested against many boxes: its candidate separating
// axes (the plane's normal and each edge crossed with each box axis) and its extent
// along each. Computed in double; a degenerate polygon (collinear vertices) is tested
// as the segment it is, since a zero axis separates nothing.
class PolygonOverlap {
public:
    static constexpr std::size_t kMaxVertices = 4;

    // Vertices coplanar, convex, in order; 1 to kMaxVertices of them.
    explicit PolygonOverlap(std::span<const glm::dvec3> v);

    // True when the polygon and the closed box [lo, hi] share a point.
    bool overlaps(const glm::dvec3& lo, const glm::dvec3& hi) const;

private:
    static constexpr std::size_t kMaxAxes = 1 + 3 * kMaxVertices;
    glm::dvec3 lo_, hi_;                       // the polygon's own box: the box axes
    std::array<glm::dvec3, kMaxAxes> axis_{};
    std::array<double, kMaxAxes> min_{}, max_{};   // the polygon's extent along each axis
    std::size_t axes_ = 0;
};

// One polygon against one box, for a single question.
inline bool polygon_overlaps_box(std::span<const glm::dvec3> v, const glm::dvec3& lo, const glm::dvec3& hi) {
    return PolygonOverlap(v).overlaps(lo, hi);
}

}  // namespace vkrt
