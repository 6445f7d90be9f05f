#pragma once
// Cones (and cone frusta) as triangle meshes: NFF's 'c' with two different radii
// (docs/nff.md). The kernel intersects cylinders exactly but has no cone primitive;
// a cone of enough sides (cone_segments) with smooth normals looks round at the size
// the scene is rendered at.
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace vkrt {

// Sides of a tessellated cone: as many as keep its silhouette within half a pixel
// of the true circle's where the camera sees it, between these bounds. The gap
// between a circle of radius r and its inscribed n-gon is r (1 - cos(pi / n)).
// At the SPD's 512 x 512, tree.nff's 4,095 cones get 6 sides each but 27 (7 to 15),
// 49,292 triangles in all; a fixed 16 sides made 131,040, and rays through the
// grid cells around the tree then ran past the loop budget.
inline constexpr std::uint32_t kMinConeSegments = 6;
inline constexpr std::uint32_t kMaxConeSegments = 64;
inline constexpr double kConeSilhouettePixels = 0.5;

// The sides for a cone seen by `camera` at its own resolution: the fewest (within the
// bounds above) for which r (1 - cos(pi / n)) is at most kConeSilhouettePixels pixels
// at the cone's nearest point to the eye (conservatively: the distance from the eye
// to its axis segment less its larger radius).
std::uint32_t cone_segments(const dvec3& base, double r0, const dvec3& apex, double r1, const Camera& camera);

// The open surface between a circle of radius r0 around `base` and one of radius r1
// around `apex`, both perpendicular to apex - base: `segments` quads of two
// triangles each, one triangle where a radius is 0 (the tip). Front faces outward
// (counter-clockwise seen from outside). Vertex normals are the cone's exact normals
// at the vertices; a tip vertex takes the normal at its triangle's middle angle, as a
// cone has none of its own there. Requires r0, r1 >= 0, not both 0, apex != base,
// segments >= 3.
std::vector<Triangle> tessellate_cone(const dvec3& base, double r0, const dvec3& apex, double r1,
                                      std::uint32_t material, std::uint32_t segments);

}  // namespace vkrt
