#pragma once
// Scene objects that expand into many primitives when the scene is loaded, so that
// the paper's big scenes (image H: 100,000 random spheres; image I: a sphereflake;
// image J: a mesh of about 86,000 triangles) stay a few lines in git
// (docs/scene-format.md).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/json_reader.hpp"
#include "scene/material_lookup.hpp"
#include "scene/scene.hpp"

namespace vkrt {

// splitmix64 (Steele, Lea and Flood 2014; Vigna's reference code). Our own rather
// than a std:: engine plus distribution, whose outputs the standard leaves to the
// implementation: a generated scene must be the same on every machine.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }

    // Uniform in [0, 1): the top 53 bits, exactly representable.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

private:
    std::uint64_t state_;
};

inline constexpr std::uint64_t kMaxRandomSpheres = 10'000'000;
inline constexpr std::uint64_t kMaxGeneratedTriangles = 20'000'000;
// 6 levels are 597,871 spheres, whose smallest are 1/729 of the biggest at the
// default ratio: already below a pixel in any view that shows the whole flake.
inline constexpr int kMaxSphereflakeLevels = 6;

// {"type": "random_spheres", "count", "seed", "min", "max", "radius", "materials"}:
// appends `count` spheres. Each draws, in this order, its centre's x, y, z (uniform
// in the box), its radius (uniform in [radius[0], radius[1]]) and its material
// (uniform over the list).
void read_random_spheres(const json::Node& n, const MaterialLookup& material, std::vector<Sphere>& out);

// How many spheres a sphereflake of `levels` levels has: 1 + 9 + ... + 9^levels,
// that is (9^(levels + 1) - 1) / 8.
constexpr std::uint64_t sphereflake_count(int levels) {
    std::uint64_t count = 0, level = 1;
    for (int i = 0; i <= levels; ++i, level *= 9) count += level;
    return count;
}

// {"type": "sphereflake", "center", "radius", "axis", "levels", "ratio", "material"}:
// appends Eric Haines' sphereflake (the SPD "balls" scene, the paper's image I).
// Every sphere of radius r carries 9 children of radius ratio * r that touch it,
// on the side away from its own parent: 6 around its equator and 3 at 54.74
// degrees above it, the directions of 9 of the 12 neighbours of a sphere in the
// densest packing, so neighbouring children are 60 degrees apart. Each child's
// children are placed the same way about the direction from its parent to it.
// The spheres are appended level by level: counting from the first one appended,
// the children of sphere k are spheres 9k + 1 to 9k + 9.
void read_sphereflake(const json::Node& n, const MaterialLookup& material, std::vector<Sphere>& out);

// A point of the (p, q) torus knot's centre line, t in [0, 2 pi): it winds p times
// around the z axis and q times around the core circle of a torus of major radius
// 2/3 * radius and minor radius 1/3 * radius, so its distance from the z axis is
// at most `radius`.
glm::dvec3 torus_knot_point(int p, int q, double radius, double t);

// {"type": "torus_knot", "p", "q", "radius", "tube", "segments", "material",
// "smooth", "transform"}: appends a tube of radius `tube` around the knot, made of
// 2 * along * around triangles with their front faces outward. Smooth normals are
// the tube's exact ones (the direction from the centre line to the vertex).
void read_torus_knot(const json::Node& n, const MaterialLookup& material, Scene& scene);

}  // namespace vkrt
