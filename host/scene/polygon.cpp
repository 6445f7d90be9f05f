// Polygon triangulation (polygon.hpp), in double like the rest of the scene.
#include "scene/polygon.hpp"

#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "scene/vec_math.hpp"

namespace vkrt {
namespace {

using glm::dvec3;

// The JSON loader's zero-area rule (kParallelSine, vec_math.hpp): a triangle whose
// edges meet at an angle with a smaller sine is left out here rather than handed on.

bool degenerate(const dvec3& a, const dvec3& b, const dvec3& c) {
    return parallel_or_zero(b - a, c - a, kParallelSine);
}

// Twice the polygon's vector area (Newell's normal), summed relative to vertex 0 so
// that a small polygon far from the origin keeps its digits.
dvec3 vector_area(std::span<const dvec3> v) {
    dvec3 n(0.0);
    for (std::size_t k = 1; k + 1 < v.size(); ++k) n += glm::cross(v[k] - v[0], v[k + 1] - v[0]);
    return n;
}

void add(PolygonTriangles& out, std::span<const dvec3> v, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (degenerate(v[a], v[b], v[c])) {
        ++out.degenerate;
    } else {
        out.triangles.push_back({a, b, c});
    }
}

void fan(std::span<const dvec3> v, PolygonTriangles& out) {
    for (std::uint32_t k = 1; k + 1 < v.size(); ++k) add(out, v, 0, k, k + 1);
}

struct Point2 {
    double x, y;
};

// Twice the signed area of (o, a, b): positive when it turns counter-clockwise.
double turn(const Point2& o, const Point2& a, const Point2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// (a, b, c) may be cut off when it turns the polygon's way and no other remaining
// vertex lies inside it or on its edges (a vertex repeated at a corner does not count).
bool is_ear(const std::vector<Point2>& p, const std::vector<std::uint32_t>& left, std::uint32_t a, std::uint32_t b,
            std::uint32_t c) {
    const Point2 &pa = p[a], &pb = p[b], &pc = p[c];
    if (!(turn(pa, pb, pc) > 0.0)) return false;
    for (const std::uint32_t k : left) {
        if (k == a || k == b || k == c) continue;
        const Point2& q = p[k];
        const auto same = [&q](const Point2& r) { return q.x == r.x && q.y == r.y; };
        if (same(pa) || same(pb) || same(pc)) continue;
        if (turn(pa, pb, q) >= 0.0 && turn(pb, pc, q) >= 0.0 && turn(pc, pa, q) >= 0.0) return false;
    }
    return true;
}

void ear_clip(std::span<const dvec3> v, const dvec3& normal, PolygonTriangles& out) {
    // Work in the coordinate plane the normal is most along, with one axis mirrored
    // when needed so that the loop runs counter-clockwise there.
    const dvec3 a = glm::abs(normal);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    const int u = (axis + 1) % 3;
    const int w = (axis + 2) % 3;
    const double flip = normal[axis] < 0.0 ? -1.0 : 1.0;
    std::vector<Point2> p(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) p[k] = {(v[k][u] - v[0][u]) * flip, v[k][w] - v[0][w]};

    std::vector<std::uint32_t> left(v.size());
    std::iota(left.begin(), left.end(), 0u);
    std::size_t i = 0;       // the vertex tried next as an ear's tip
    std::size_t misses = 0;  // tips tried since the last cut
    while (left.size() > 3) {
        const std::size_t m = left.size();
        const std::uint32_t prev = left[(i + m - 1) % m];
        const std::uint32_t next = left[(i + 1) % m];
        if (is_ear(p, left, prev, left[i], next)) {
            add(out, v, prev, left[i], next);
        } else if (++misses < m) {
            i = (i + 1) % m;
            continue;
        } else {
            // A whole round without an ear: a simple polygon then still has a
            // zero-area corner to drop, which loses no surface. Without one its
            // edges cross, and the fan is as good a guess as any.
            std::size_t k = 0;
            while (k < m && !degenerate(v[left[(k + m - 1) % m]], v[left[k]], v[left[(k + 1) % m]])) ++k;
            if (k == m) {
                out.simple = false;
                for (std::size_t j = 1; j + 1 < m; ++j) add(out, v, left[0], left[j], left[j + 1]);
                return;
            }
            ++out.degenerate;
            i = k;
        }
        left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
        if (i == left.size()) i = 0;
        misses = 0;
    }
    add(out, v, left[0], left[1], left[2]);
}

}  // namespace

bool polygon_is_convex(std::span<const dvec3> v) {
    const dvec3 n = vector_area(v);
    if (!is_nonzero(n)) return false;
    const dvec3 axis = robust_normalize(n);
    for (std::size_t i = 0; i < v.size(); ++i) {
        const dvec3 e1 = v[i] - v[(i + v.size() - 1) % v.size()];
        const dvec3 e2 = v[(i + 1) % v.size()] - v[i];
        // A turn against the normal by more than the degenerate-angle tolerance.
        if (glm::dot(glm::cross(e1, e2), axis) < -kParallelSine * glm::length(e1) * glm::length(e2)) return false;
    }
    return true;
}

PolygonTriangles triangulate_polygon(std::span<const dvec3> vertices) {
    PolygonTriangles out;
    const dvec3 n = vector_area(vertices);
    if (!is_nonzero(n)) {
        // No area at all: collinear vertices (all degenerate), or a figure eight
        // whose halves cancel, which is not simple.
        fan(vertices, out);
        out.simple = out.triangles.empty();
    } else if (polygon_is_convex(vertices)) {
        fan(vertices, out);
    } else {
        ear_clip(vertices, n, out);
    }
    return out;
}

}  // namespace vkrt
