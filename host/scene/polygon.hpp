#pragma once
// Splitting a polygon, given as its loop of vertices, into triangles: scene formats
// state polygons (NFF's p and pp), the kernel intersects only triangles.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace vkrt {

struct PolygonTriangles {
    // Corners as indices into the polygon's vertices, in the polygon's own turning
    // order, so every triangle keeps the polygon's front face.
    std::vector<std::array<std::uint32_t, 3>> triangles;
    // Zero-area triangles left out (repeated or collinear vertices): they cover
    // nothing, and the kernel's triangle test has no orientation for them.
    std::uint32_t degenerate = 0;
    // False when the polygon is neither convex nor simple (its edges cross), so no
    // set of triangles matches it; it was then split as a fan from vertex 0.
    bool simple = true;
};

// Ear clipping costs up to the cube of the vertex count; convex polygons (a fan, of
// any size) do not. Beyond this a non-convex polygon is refused, not split slowly.
inline constexpr std::size_t kMaxConcavePolygonVertices = 1024;

// True when every turn of the loop goes the same way around the polygon's normal
// (collinear and repeated vertices allowed): then the fan from vertex 0 is exact.
bool polygon_is_convex(std::span<const glm::dvec3> vertices);

// A convex polygon becomes the fan (0, k, k + 1), the split every NFF reader makes.
// A non-convex one (SPD gears' faces, whose outline has teeth) is split by ear
// clipping in its plane: a fan would cover the gaps between the teeth.
// Expects at least 3 vertices.
PolygonTriangles triangulate_polygon(std::span<const glm::dvec3> vertices);

}  // namespace vkrt
