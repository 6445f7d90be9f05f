#pragma once
// Cones (and cone frusta) as triangle meshes: NFF's 'c' with two different radii
// (docs/nff.md). The kernel intersects cylinders exactly but has no cone primitive;
// a cone of kConeSegments sides with smooth normals looks round enough at the sizes
// the SPD scenes are rendered at.
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace vkrt {

// Sides of a tessellated cone. At the SPD's 512 x 512, tree.nff's worst cone (the
// largest radius for its distance from the eye) needs 10 sides for the polygon's
// silhouette to stay within a pixel of the circle's (the gap is r (1 - cos(pi / n)));
// 16 keep it within 0.4 pixels.
inline constexpr std::uint32_t kConeSegments = 16;

// The open surface between a circle of radius r0 around `base` and one of radius r1
// around `apex`, both perpendicular to apex - base: `segments` quads of two
// triangles each, one triangle where a radius is 0 (the tip). Front faces outward
// (counter-clockwise seen from outside). Vertex normals are the cone's exact normals
// at the vertices; a tip vertex takes the normal at its triangle's middle angle, as a
// cone has none of its own there. Requires r0, r1 >= 0, not both 0, apex != base,
// segments >= 3.
std::vector<Triangle> tessellate_cone(const dvec3& base, double r0, const dvec3& apex, double r1,
                                      std::uint32_t material, std::uint32_t segments = kConeSegments);

}  // namespace vkrt
