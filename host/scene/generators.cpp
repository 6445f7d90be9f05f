#include "scene/generators.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>

#include <array>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "scene/indexed_mesh.hpp"
#include "scene/transform.hpp"
#include "scene/vec_math.hpp"

namespace vkrt {

using glm::dvec3;

void read_random_spheres(const json::Node& n, const MaterialLookup& material, std::vector<Sphere>& out) {
    n.allow_only({"type", "count", "seed", "min", "max", "radius", "materials"});
    const std::uint64_t count = n.required("count").whole(1, kMaxRandomSpheres);
    std::uint64_t seed = 1;
    if (auto s = n.find("seed")) seed = s->whole(0, std::numeric_limits<std::uint32_t>::max());
    const dvec3 lo = n.required("min").vec3();
    const json::Node max_node = n.required("max");
    const dvec3 hi = max_node.vec3();
    for (int i = 0; i < 3; ++i) {
        if (hi[i] < lo[i]) {
            max_node.fail(fmt::format("expected max >= min in every component, but max {} and min {} differ in [{}]",
                                      json::format_vec3(hi), json::format_vec3(lo), i));
        }
    }
    const auto radius = n.required("radius").elements(2, "an array [smallest, largest] of 2 numbers");
    const double r_lo = radius[0].number_above(0.0);
    const double r_hi = radius[1].number();
    if (r_hi < r_lo) radius[1].fail(fmt::format("expected a number >= radius[0] ({}), got {}", r_lo, r_hi));
    const json::Node list = n.required("materials");
    std::vector<std::uint32_t> materials;
    for (const json::Node& name : list.elements()) materials.push_back(material(name));
    if (materials.empty()) list.fail("expected at least one material name, got an empty array");

    SplitMix64 rng(seed);
    for (std::uint64_t i = 0; i < count; ++i) {
        Sphere s;
        for (int k = 0; k < 3; ++k) s.center[k] = lo[k] + rng.uniform() * (hi[k] - lo[k]);
        s.radius = r_lo + rng.uniform() * (r_hi - r_lo);
        // uniform() < 1, so the index is below the list's size.
        s.material = materials[static_cast<std::size_t>(rng.uniform() * static_cast<double>(materials.size()))];
        out.push_back(s);
    }
}

namespace {

// A sphere's own frame: columns u, v in its equatorial plane and w, the direction
// its children grow towards, right-handed (u x v = w).
using Frame = glm::dmat3;

// The 9 children of a sphere in its own frame: child k sits in direction column 2
// of kChildFrames[k], and that matrix, taking the parent's frame to the child's,
// is the rotation Rz(phi) Ry(90 deg - theta) that carries the parent's w onto that
// direction (elevation theta, azimuth phi). Applying the same rotations at every
// level makes each child's subtree an exact scaled copy of the whole flake.
//
// Elevation and azimuths: around one sphere, 12 equal spheres touching it can
// touch their neighbours too (the densest packing: a hexagon in the equator, and
// triangles of 3 above and below, turned 30 degrees against the hexagon). The
// sphereflake keeps the hexagon (theta 0; phi 0, 60, ..., 300) and the upper
// triangle (phi 30, 150, 270), whose elevation theta has sin^2 = 2/3 (54.74 deg):
// then no two children are less than 60 degrees apart (a ring child has 3 siblings
// at 60, a top child 4), and siblings at 60 degrees do not overlap as long as the
// ratio is below 1 (their centres are (1 + ratio) r apart, their radii add up to
// 2 ratio r). The 3 below the equator would point back at the
// parent, so they are left out.
std::array<glm::dmat3, 9> child_frames() {
    std::array<glm::dmat3, 9> frames{};
    const double sin_up = std::sqrt(2.0 / 3.0), cos_up = std::sqrt(1.0 / 3.0);
    for (int k = 0; k < 9; ++k) {
        const bool ring = k < 6;
        const double phi = (ring ? 60.0 * k : 30.0 + 120.0 * (k - 6)) * std::numbers::pi / 180.0;
        const double st = ring ? 0.0 : sin_up, ct = ring ? 1.0 : cos_up;
        const double sp = std::sin(phi), cp = std::cos(phi);
        frames[k] = glm::dmat3(dvec3(st * cp, st * sp, -ct),  // u: Ry turns x down to (sin t, 0, -cos t)
                               dvec3(-sp, cp, 0.0),           // v
                               dvec3(ct * cp, ct * sp, st));  // w: the child's direction
    }
    return frames;
}

// The root's frame: w along the axis, u the world axis x (or z, when the axis is
// nearly x) made perpendicular to it. For the default axis y that gives u = x,
// v = -z: one of the upper children then faces +z.
Frame root_frame(const dvec3& axis) {
    const dvec3 w = glm::normalize(axis);
    const dvec3 e = std::abs(w.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 0, 1);
    const dvec3 u = glm::normalize(e - glm::dot(e, w) * w);
    return Frame(u, glm::cross(w, u), w);
}

}  // namespace

void read_sphereflake(const json::Node& n, const MaterialLookup& material, std::vector<Sphere>& out) {
    n.allow_only({"type", "center", "radius", "axis", "levels", "ratio", "material"});
    const dvec3 center = n.required("center").vec3();
    const double radius = n.required("radius").number_above(0.0);
    dvec3 axis(0, 1, 0);
    if (auto a = n.find("axis")) {
        axis = a->vec3();
        if (!is_nonzero(axis)) a->fail("expected a non-zero vector, got [0, 0, 0]");
        axis = robust_normalize(axis);
    }
    int levels = 4;
    if (auto l = n.find("levels")) levels = static_cast<int>(l->whole(0, kMaxSphereflakeLevels));
    double ratio = 1.0 / 3.0;
    if (auto r = n.find("ratio")) {
        ratio = r->number_above(0.0);
        if (ratio > 1.0) r->fail(fmt::format("expected a number in (0, 1], got {}", ratio));
    }
    // The renderer gets floats: the smallest spheres must not round to radius 0.
    const double smallest = radius * std::pow(ratio, levels);
    if (!(static_cast<float>(smallest) >= std::numeric_limits<float>::min())) {
        n.fail(fmt::format("the smallest spheres' radius {} (radius x ratio^levels) is too small for the "
                           "renderer's single precision; use fewer levels or a larger ratio",
                           smallest));
    }
    const std::uint32_t m = material(n.required("material"));

    static const std::array<glm::dmat3, 9> kChildFrames = child_frames();
    const std::size_t first = out.size();
    out.reserve(first + sphereflake_count(levels));
    out.push_back(Sphere{center, radius, m});
    std::vector<Frame> frames{root_frame(axis)};
    frames.reserve(1 + sphereflake_count(levels - 1));
    // Level by level; sphere k of the flake (k counted from `first`) is frames[k].
    std::size_t begin = 0, end = 1;
    for (int level = 0; level < levels; ++level) {
        for (std::size_t k = begin; k < end; ++k) {
            const Sphere parent = out[first + k];
            const double r = parent.radius * ratio;
            for (const glm::dmat3& turn : kChildFrames) {
                const Frame child = frames[k] * turn;
                out.push_back(Sphere{parent.center + (parent.radius + r) * child[2], r, m});
                // The last level's frames would never be read.
                if (level + 1 < levels) frames.push_back(child);
            }
        }
        begin = end;
        end = out.size() - first;
    }
}

dvec3 torus_knot_point(int p, int q, double radius, double t) {
    const double rho = radius * (2.0 + std::cos(q * t)) / 3.0;
    return {rho * std::cos(p * t), rho * std::sin(p * t), radius * std::sin(q * t) / 3.0};
}

namespace {

struct Knot {
    int p = 2;
    int q = 3;
    double radius = 1.0;
    double tube = 0.25;
    std::uint32_t along = 256;
    std::uint32_t around = 16;
};

// Vertex (i, j) is ring i along the knot, angle j around the tube; index i * around + j.
// The frame at each ring: N, the normal of the torus the knot lies on (from the
// torus's core circle to the knot), which is perpendicular to the knot's tangent T
// because the knot lies on that torus; and B = T x N. Unlike the Frenet frame it
// never flips, and it closes up after one turn because p and q are whole numbers.
IndexedMesh knot_mesh(const Knot& k) {
    IndexedMesh mesh;
    const std::size_t vertices = std::size_t(k.along) * k.around;
    mesh.positions.reserve(vertices);
    mesh.normals.reserve(vertices);
    const double third = k.radius / 3.0;
    for (std::uint32_t i = 0; i < k.along; ++i) {
        const double t = 2.0 * std::numbers::pi * i / k.along;
        const double cp = std::cos(k.p * t), sp = std::sin(k.p * t);
        const double cq = std::cos(k.q * t), sq = std::sin(k.q * t);
        const dvec3 centre = torus_knot_point(k.p, k.q, k.radius, t);
        const double rho = third * (2.0 + cq);
        const double drho = -third * k.q * sq;
        const dvec3 tangent = glm::normalize(dvec3(drho * cp - rho * k.p * sp, drho * sp + rho * k.p * cp, third * k.q * cq));
        dvec3 normal(cq * cp, cq * sp, sq);
        normal = glm::normalize(normal - glm::dot(normal, tangent) * tangent);  // orthogonal to rounding too
        const dvec3 binormal = glm::cross(tangent, normal);
        for (std::uint32_t j = 0; j < k.around; ++j) {
            const double theta = 2.0 * std::numbers::pi * j / k.around;
            const dvec3 out = std::cos(theta) * normal + std::sin(theta) * binormal;
            mesh.positions.push_back(centre + k.tube * out);
            mesh.normals.push_back(out);
        }
    }
    // Quad (i, j)-(i+1, j)-(i+1, j+1)-(i, j+1) as two triangles wound so that
    // cross(edge around, edge along) = cross(B, T) = N points out of the tube.
    mesh.faces.reserve(2 * vertices);
    const auto index = [&](std::uint32_t i, std::uint32_t j) {
        return static_cast<std::uint32_t>((i % k.along) * k.around + j % k.around);
    };
    for (std::uint32_t i = 0; i < k.along; ++i) {
        for (std::uint32_t j = 0; j < k.around; ++j) {
            const std::uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
            mesh.faces.push_back({{a, d, c}, {a, d, c}});
            mesh.faces.push_back({{a, c, b}, {a, c, b}});
        }
    }
    return mesh;
}

}  // namespace

void read_torus_knot(const json::Node& n, const MaterialLookup& material, Scene& scene) {
    n.allow_only({"type", "p", "q", "radius", "tube", "segments", "material", "smooth", "transform"});
    Knot k;
    // Beyond a thousand windings the tube is thinner than any sensible tessellation.
    if (auto p = n.find("p")) k.p = static_cast<int>(p->whole(1, 1000));
    if (auto q = n.find("q")) k.q = static_cast<int>(q->whole(1, 1000));
    if (auto r = n.find("radius")) k.radius = r->number_above(0.0);
    if (auto t = n.find("tube")) k.tube = t->number_above(0.0);
    if (auto s = n.find("segments")) {
        const auto e = s->elements(2, "an array [along, around] of 2 whole numbers");
        k.along = static_cast<std::uint32_t>(e[0].whole(3, kMaxGeneratedTriangles / 6));
        k.around = static_cast<std::uint32_t>(e[1].whole(3, kMaxGeneratedTriangles / 6));
        if (2 * std::uint64_t(k.along) * k.around > kMaxGeneratedTriangles) {
            s->fail(fmt::format("{} x {} segments make {} triangles, more than the limit of {}", k.along, k.around,
                                2 * std::uint64_t(k.along) * k.around, kMaxGeneratedTriangles));
        }
    }
    MeshOptions options;
    options.material = material(n.required("material"));
    if (auto smooth = n.find("smooth")) options.smooth = smooth->boolean();
    const std::optional<json::Node> transform = n.find("transform");
    const Transform t = transform ? read_transform(*transform) : Transform{};
    add_mesh(n, knot_mesh(k), t, transform, options, scene);
}

}  // namespace vkrt
