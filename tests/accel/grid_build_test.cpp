// Grid construction on the host (host/accel/grid.cpp, grid_split.cpp): the resolution
// heuristic, and the flattened arrays: every primitive listed in exactly the cells its
// padded box overlaps (a triangle: the padded cells its polygon overlaps), the nodes a
// prefix sum of the cell sizes, split cells' children at every depth.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <random>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "accel/box_overlap.hpp"
#include "accel/grid.hpp"
#include "scene/scene.hpp"  // each kind's bounds()

namespace {

using namespace vkrt;
namespace kernel = vkrt::kernel;
using glm::dvec3;

kernel::Sphere sphere(glm::vec3 c, float r) { return kernel::Sphere{kernel::vec4(c, r), kernel::uvec4(0u)}; }

kernel::Triangle triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    kernel::Triangle t{};
    t.p0 = kernel::vec4(a, 0.0f);
    t.p1 = kernel::vec4(b, 0.0f);
    t.p2 = kernel::vec4(c, 0.0f);
    return t;
}

kernel::Ring ring(glm::vec3 c, glm::vec3 n, float inner, float outer) {
    return kernel::Ring{kernel::vec4(c, inner), kernel::vec4(glm::normalize(n), outer), kernel::uvec4(0u)};
}

kernel::Cylinder cylinder(glm::vec3 base, glm::vec3 top, float r, bool capped) {
    return kernel::Cylinder{kernel::vec4(base, r), kernel::vec4(top, capped ? 1.0f : 0.0f), kernel::uvec4(0u)};
}

struct RandomScene {
    std::vector<kernel::Sphere> spheres;
    std::vector<kernel::Triangle> triangles;
    std::vector<kernel::Ring> rings;
    std::vector<kernel::Cylinder> cylinders;

    GridPrimitives primitives() const { return {spheres, triangles, rings, cylinders}; }
    std::size_t size() const { return spheres.size() + triangles.size() + rings.size() + cylinders.size(); }
};

// Spheres and triangles, and a quarter as many rings and cylinders of each.
RandomScene random_scene(std::uint32_t seed, int spheres, int triangles) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f);
    std::uniform_real_distribution<float> size(0.01f, 2.0f);
    std::uniform_real_distribution<float> dir(-1.0f, 1.0f);
    RandomScene s;
    for (int i = 0; i < spheres; ++i) s.spheres.push_back(sphere({pos(rng), pos(rng), pos(rng)}, size(rng)));
    for (int i = 0; i < triangles; ++i) {
        const glm::vec3 a(pos(rng), pos(rng), pos(rng));
        const glm::vec3 d1(size(rng), size(rng), -size(rng));
        const glm::vec3 d2(-size(rng), size(rng), size(rng));
        s.triangles.push_back(triangle(a, a + d1, a + d2));
    }
    for (int i = 0; i < (spheres + triangles) / 4; ++i) {
        const float outer = size(rng);
        s.rings.push_back(ring({pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng) + 0.01f}, 0.3f * outer,
                               outer));
        const glm::vec3 base(pos(rng), pos(rng), pos(rng));
        s.cylinders.push_back(
            cylinder(base, base + 2.0f * glm::vec3(dir(rng), dir(rng), dir(rng) + 0.01f), 0.5f * size(rng), i % 2 == 0));
    }
    return s;
}

std::uint64_t cells(const GridResolution& r) { return std::uint64_t(r[0]) * r[1] * r[2]; }

TEST(GridResolution, WoosRuleCellsProportionalToExtent) {
    // A 4 x 2 x 1 box with 1000 primitives at density 8: k^3 * 8 = 8000, k = 10.
    const GridResolution r = grid_resolution(Aabb{dvec3(0.0), dvec3(4.0, 2.0, 1.0)}, 1000, 8.0, 1u << 30);
    EXPECT_EQ(r, (GridResolution{40, 20, 10}));
}

TEST(GridResolution, FlatAxesGetOneCellAndLeaveTheBudgetToTheOthers) {
    // Zero extent on z: the 8,000 cells are shared by x and y alone.
    const GridResolution r = grid_resolution(Aabb{dvec3(0.0), dvec3(2.0, 2.0, 0.0)}, 1000, 8.0, 1u << 30);
    EXPECT_EQ(r, (GridResolution{89, 89, 1}));
    // A thin slab: z would get less than one cell by the cube root, so it gets one.
    const GridResolution thin = grid_resolution(Aabb{dvec3(0.0), dvec3(10.0, 10.0, 0.001)}, 100, 1.0, 1u << 30);
    EXPECT_EQ(thin, (GridResolution{10, 10, 1}));
    // A line.
    const GridResolution line = grid_resolution(Aabb{dvec3(0.0), dvec3(0.0, 0.0, 5.0)}, 10, 2.0, 1u << 30);
    EXPECT_EQ(line, (GridResolution{1, 1, 20}));
}

TEST(GridResolution, OnePrimitiveAndEmptyAndCapped) {
    EXPECT_EQ(grid_resolution(Aabb{dvec3(0.0), dvec3(1.0)}, 1, 1.0, 1u << 30), (GridResolution{1, 1, 1}));
    EXPECT_EQ(grid_resolution(Aabb{dvec3(0.0), dvec3(1.0)}, 0, 8.0, 1u << 30), (GridResolution{1, 1, 1}));
    EXPECT_EQ(grid_resolution(Aabb{dvec3(0.0), dvec3(0.0)}, 5, 8.0, 1u << 30), (GridResolution{1, 1, 1}));
    const GridResolution capped = grid_resolution(Aabb{dvec3(0.0), dvec3(1.0)}, 1000000, 8.0, 1000);
    EXPECT_LE(cells(capped), 1000u);
    EXPECT_GE(cells(capped), 500u);
}

// The references of node k, a leaf: from its offset to the next node's.
std::vector<std::uint32_t> leaf_refs(const Grid& g, std::uint64_t k) {
    EXPECT_EQ(g.nodes[k] & kernel::GRID_INNER, 0u) << "node " << k << " is split";
    if ((g.nodes[k] & kernel::GRID_INNER) != 0) return {};
    return {g.refs.begin() + g.nodes[k], g.refs.begin() + (g.nodes[k + 1] & ~kernel::GRID_INNER)};
}

// Every primitive's box and its reference, kind by kind in the kernel's order.
std::pair<std::vector<Aabb>, std::vector<std::uint32_t>> boxes_and_refs(const RandomScene& s) {
    std::vector<Aabb> boxes;
    std::vector<std::uint32_t> refs;
    auto add = [&](const auto& items, std::uint32_t kind) {
        for (std::uint32_t i = 0; i < items.size(); ++i) {
            boxes.push_back(bounds(items[i]));
            refs.push_back((kind << kernel::REF_KIND_SHIFT) | i);
        }
    };
    add(s.spheres, kernel::REF_SPHERE);
    add(s.triangles, kernel::REF_TRIANGLE);
    add(s.rings, kernel::REF_RING);
    add(s.cylinders, kernel::REF_CYLINDER);
    return {boxes, refs};
}

// Rebuilds, by brute force over cells, the set of references each cell should hold,
// and compares it with the flattened arrays.
void expect_exact_binning(const Grid& g, const RandomScene& s) {
    const std::uint64_t n = g.cell_count();
    ASSERT_EQ(g.levels, 0u) << "a grid without splits";
    ASSERT_EQ(g.nodes.size(), n + 1);
    EXPECT_EQ(g.nodes.front(), g.loose) << "the loose references come before cell 0's";
    const std::vector<std::uint32_t> loose(g.refs.begin(), g.refs.begin() + g.loose);
    EXPECT_EQ(g.nodes.back(), g.refs.size());
    EXPECT_TRUE(std::is_sorted(g.nodes.begin(), g.nodes.end())) << "not a prefix sum";

    std::vector<std::vector<std::uint32_t>> want(n);
    // A triangle goes into the cells of its box that, grown by the padding, its
    // polygon overlaps.
    auto bin = [&](const Aabb& box, std::uint32_t ref, const kernel::Triangle* tri = nullptr) {
        if (std::find(loose.begin(), loose.end(), ref) != loose.end()) return;  // in no cell
        const auto [first, last] = g.cells_overlapping(box);
        for (std::uint32_t z = 0; z < g.resolution[2]; ++z) {
            for (std::uint32_t y = 0; y < g.resolution[1]; ++y) {
                for (std::uint32_t x = 0; x < g.resolution[0]; ++x) {
                    bool inside = x >= first[0] && x <= last[0] && y >= first[1] && y <= last[1] &&
                                  z >= first[2] && z <= last[2];
                    if (inside && tri != nullptr) {
                        const std::array<dvec3, 3> v{dvec3(tri->p0.x, tri->p0.y, tri->p0.z),
                                                     dvec3(tri->p1.x, tri->p1.y, tri->p1.z),
                                                     dvec3(tri->p2.x, tri->p2.y, tri->p2.z)};
                        const dvec3 pad = g.padding(box);
                        const dvec3 lo = g.lo + g.cell * dvec3(x, y, z) - pad;
                        inside = polygon_overlaps_box(v, lo, lo + g.cell + 2.0 * pad);
                    }
                    if (inside) want[(std::uint64_t(z) * g.resolution[1] + y) * g.resolution[0] + x].push_back(ref);
                }
            }
        }
    };
    for (std::uint32_t i = 0; i < s.spheres.size(); ++i) {
        bin(bounds(s.spheres[i]), (kernel::REF_SPHERE << kernel::REF_KIND_SHIFT) | i);
    }
    for (std::uint32_t i = 0; i < s.triangles.size(); ++i) {
        bin(bounds(s.triangles[i]), (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | i, &s.triangles[i]);
    }
    for (std::uint32_t i = 0; i < s.rings.size(); ++i) {
        bin(bounds(s.rings[i]), (kernel::REF_RING << kernel::REF_KIND_SHIFT) | i);
    }
    for (std::uint32_t i = 0; i < s.cylinders.size(); ++i) {
        bin(bounds(s.cylinders[i]), (kernel::REF_CYLINDER << kernel::REF_KIND_SHIFT) | i);
    }
    for (std::uint64_t c = 0; c < n; ++c) {
        ASSERT_EQ(leaf_refs(g, c), want[c]) << "cell " << c;
    }
}

TEST(GridBuild, EveryPrimitiveIsInExactlyTheCellsItOverlaps) {
    const RandomScene s = random_scene(7, 300, 200);
    std::string note;
    const Grid g = build_grid(s.primitives(), GridRequest{}, note);
    EXPECT_TRUE(note.empty()) << note;
    EXPECT_GT(cells(g.resolution), 1000u);
    expect_exact_binning(g, s);
}

TEST(GridBuild, CellsCoverEveryBoxWithPadding) {
    // The padded overlap really covers each box: its corners fall into the listed
    // cells by the same arithmetic the kernel uses for a point.
    const RandomScene s = random_scene(11, 500, 0);
    std::string note;
    const Grid g = build_grid(s.primitives(), GridRequest{}, note);
    for (const kernel::Sphere& sp : s.spheres) {
        const Aabb b = bounds(sp);
        const auto [first, last] = g.cells_overlapping(b);
        for (int a = 0; a < 3; ++a) {
            const double lo_cell = std::floor((b.lo[a] - g.lo[a]) / g.cell[a]);
            const double hi_cell = std::floor((b.hi[a] - g.lo[a]) / g.cell[a]);
            EXPECT_LE(first[a], std::max(0.0, lo_cell));
            EXPECT_GE(last[a], std::min(double(g.resolution[a] - 1), hi_cell));
        }
    }
    // The box contains every primitive and its corners are floats.
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(double(float(g.lo[a])), g.lo[a]);
        EXPECT_EQ(double(float(g.cell[a])), g.cell[a]);
        EXPECT_GE(g.hi[a], g.lo[a] + g.cell[a] * (g.resolution[a] - 0.5));
    }
}

TEST(GridBuild, RequestedResolutionIsUsedAndClampedToTheDeviceLimit) {
    const RandomScene s = random_scene(3, 50, 50);
    std::string note;
    GridRequest request;
    request.resolution = {3, 4, 5};
    const Grid g = build_grid(s.primitives(), request, note);
    EXPECT_EQ(g.resolution, (GridResolution{3, 4, 5}));
    EXPECT_TRUE(note.empty());
    expect_exact_binning(g, s);

    request.resolution = {100, 100, 100};
    request.max_entries = 20001;  // 20,000 cells at most
    const Grid clamped = build_grid(s.primitives(), request, note);
    EXPECT_LE(clamped.cell_count() + 1, 20001u);
    EXPECT_LE(clamped.refs.size(), 20001u);
    EXPECT_NE(note.find("exceeds this device's buffer limit"), std::string::npos) << note;
    expect_exact_binning(clamped, s);
}

TEST(GridBuild, TooManyReferencesCoarsensTheGrid) {
    // Big triangles over a fine grid: each is copied into many cells. A small entry
    // limit forces coarser cells until the references fit.
    RandomScene s;
    for (int i = 0; i < 20; ++i) {
        const float x = float(i) * 0.01f;
        s.triangles.push_back(triangle({x, 0, 0}, {10, x, 10}, {0, 10, 10 - x}));
    }
    std::string note;
    GridRequest request;
    request.resolution = {40, 40, 20};  // 32,000 cells, each holding every triangle
    request.max_entries = 40000;
    const Grid g = build_grid(s.primitives(), request, note);
    EXPECT_LE(g.refs.size(), 40000u);
    EXPECT_LT(g.cell_count(), 32000u);
    EXPECT_NE(note.find("references"), std::string::npos) << note;
    expect_exact_binning(g, s);
}

// A floor far wider than the rest (SPD tree: 100 units under a tree 3 across) is
// left loose: tested per ray, listed in no cell, so that the grid's box and cells are
// the cluster's.
TEST(GridBuild, PrimitivesThatStretchTheBoxAreLeftLoose) {
    RandomScene s = random_scene(29, 200, 100);   // within [-12, 12] on every axis
    s.triangles.push_back(triangle({-500, -500, -11}, {500, -500, -11}, {500, 500, -11}));
    s.triangles.push_back(triangle({-500, -500, -11}, {500, 500, -11}, {-500, 500, -11}));
    const std::uint32_t floor0 = (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | 100u;
    std::string note;
    GridRequest request;
    request.max_loose = 32;
    const Grid g = build_grid(s.primitives(), request, note);
    ASSERT_EQ(g.loose, 2u);
    EXPECT_EQ(g.refs[0], floor0);
    EXPECT_EQ(g.refs[1], floor0 + 1u);
    EXPECT_GT(g.loose_shrink, 1000.0);
    for (int a = 0; a < 3; ++a) {
        EXPECT_GT(g.lo[a], -13.0) << "axis " << a;
        EXPECT_LT(g.hi[a], 13.0) << "axis " << a;
    }
    expect_exact_binning(g, s);
    for (std::uint64_t i = g.loose; i < g.refs.size(); ++i) {
        ASSERT_TRUE(g.refs[i] != floor0 && g.refs[i] != floor0 + 1u) << "a loose primitive is listed in a cell too";
    }

    // With max_loose = 0 (a grid asked for over everything): the floor sets the box.
    // Unsplit, for expect_exact_binning.
    request.max_loose = 0;
    request.split = false;
    const Grid all = build_grid(s.primitives(), request, note);
    EXPECT_EQ(all.loose, 0u);
    EXPECT_LT(all.lo.x, -499.0);
    expect_exact_binning(all, s);
}

TEST(GridBuild, NothingIsLeftLooseUnlessTheBoxShrinksMuch) {
    GridRequest request;
    request.max_loose = 32;
    std::string note;
    // Primitives of similar sizes: leaving any out barely moves the box.
    const RandomScene similar = random_scene(31, 200, 100);
    EXPECT_EQ(build_grid(similar.primitives(), request, note).loose, 0u);
    // A big sphere in the middle of the cluster stretches nothing.
    RandomScene centred = similar;
    centred.spheres.push_back(sphere({0, 0, 0}, 11.0f));
    EXPECT_EQ(build_grid(centred.primitives(), request, note).loose, 0u);
    // More wide primitives than may be loose (a stadium, tests/scenes/stability case
    // 6): leaving out 32 of these 40 still leaves their box.
    RandomScene stadium = similar;
    for (int i = 0; i < 40; ++i) {
        const float z = -11.0f - 0.1f * float(i);
        stadium.triangles.push_back(triangle({-500, -500, z}, {500, -500, z}, {0, 500, z}));
    }
    EXPECT_EQ(build_grid(stadium.primitives(), request, note).loose, 0u);
    // Walls far larger than the floor's 32 triangles, which are far larger than the
    // cluster (case 6): without the walls the floor would still set the box.
    RandomScene room = similar;
    for (int i = 0; i < 16; ++i) {
        const float x = -400.0f + 200.0f * float(i % 4), y = -400.0f + 200.0f * float(i / 4);
        room.triangles.push_back(triangle({x, y, -11}, {x + 200, y, -11}, {x, y + 200, -11}));
        room.triangles.push_back(triangle({x + 200, y, -11}, {x + 200, y + 200, -11}, {x, y + 200, -11}));
    }
    for (int i = 0; i < 8; ++i) {
        const float side = i % 2 == 0 ? -400.0f : 400.0f;
        const glm::vec3 a = i < 4 ? glm::vec3(side, -400, -11) : glm::vec3(-400, side, -11);
        const glm::vec3 b = i < 4 ? glm::vec3(side, 400, -11) : glm::vec3(400, side, -11);
        const glm::vec3 up = (i / 2) % 2 == 0 ? b : a;
        room.triangles.push_back(triangle(a, b, up + glm::vec3(0, 0, 800)));
    }
    EXPECT_EQ(build_grid(room.primitives(), request, note).loose, 0u);
}

TEST(GridBuild, FlatSceneAndSinglePrimitive) {
    // All triangles in the plane z = 0: the grid still has positive cell sizes.
    RandomScene flat;
    for (int i = 0; i < 100; ++i) {
        const float x = float(i % 10), y = float(i / 10);
        flat.triangles.push_back(triangle({x, y, 0}, {x + 1, y, 0}, {x, y + 1, 0}));
    }
    std::string note;
    const Grid g = build_grid(flat.primitives(), GridRequest{}, note);
    EXPECT_EQ(g.resolution[2], 1u);
    EXPECT_GT(g.cell[2], 0.0);
    expect_exact_binning(g, flat);

    RandomScene one;
    one.spheres.push_back(sphere({1e5f, -1e5f, 3.0f}, 0.5f));
    const Grid single = build_grid(one.primitives(), GridRequest{}, note);
    EXPECT_GE(single.cell_count(), 1u);
    expect_exact_binning(single, one);
}

// The triangle's points are sampled this far apart at most (its edges are at most
// 2 * sqrt(3) * 2 long in random_scene).
constexpr int kSamplesPerEdge = 200;
constexpr double kSampleSpacing = 7.0 / kSamplesPerEdge;

// The distance from the closed box [lo, hi] to the nearest of the triangle's sampled
// points: 0 when one lies inside.
double distance_to_box(const kernel::Triangle& t, const dvec3& lo, const dvec3& hi) {
    const dvec3 a(t.p0.x, t.p0.y, t.p0.z), b(t.p1.x, t.p1.y, t.p1.z), c(t.p2.x, t.p2.y, t.p2.z);
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kSamplesPerEdge; ++i) {
        for (int j = 0; i + j <= kSamplesPerEdge; ++j) {
            const dvec3 p = a + (b - a) * (double(i) / kSamplesPerEdge) + (c - a) * (double(j) / kSamplesPerEdge);
            nearest = std::min(nearest, glm::length(glm::max(glm::max(lo - p, p - hi), dvec3(0.0))));
        }
    }
    return nearest;
}

TEST(GridBuild, CellsListedAreThoseThePrimitiveTouchesByGeometry) {
    // Independent of cells_overlapping and of the overlap test: a cell must hold a
    // primitive when the cell's slab intersects the primitive's box on every axis (a
    // triangle: when one of its sampled points lies in the cell), and may hold it only
    // when it intersects the box grown by twice the padding (a triangle: when a sample
    // lies within twice the padding and the samples' spacing).
    const RandomScene s = random_scene(13, 120, 80);
    std::string note;
    const Grid g = build_grid(s.primitives(), GridRequest{}, note);
    const auto [boxes, refs] = boxes_and_refs(s);
    auto listed = [&](std::uint64_t cell, std::uint32_t i) {
        const std::vector<std::uint32_t> in = leaf_refs(g, cell);
        return std::find(in.begin(), in.end(), refs[i]) != in.end();
    };
    for (std::uint32_t z = 0; z < g.resolution[2]; ++z) {
        for (std::uint32_t y = 0; y < g.resolution[1]; ++y) {
            for (std::uint32_t x = 0; x < g.resolution[0]; ++x) {
                const dvec3 lo = g.lo + g.cell * dvec3(x, y, z);
                const dvec3 hi = lo + g.cell;
                const std::uint64_t cell = (std::uint64_t(z) * g.resolution[1] + y) * g.resolution[0] + x;
                for (std::uint32_t i = 0; i < boxes.size(); ++i) {
                    const Aabb& b = boxes[i];
                    bool touches = glm::all(glm::lessThanEqual(b.lo, hi)) && glm::all(glm::lessThanEqual(lo, b.hi));
                    bool near = glm::all(glm::lessThanEqual(b.lo - 2.0 * g.pad, hi)) &&
                                glm::all(glm::lessThanEqual(lo, b.hi + 2.0 * g.pad));
                    if ((refs[i] >> kernel::REF_KIND_SHIFT) == kernel::REF_TRIANGLE && near) {
                        // A triangle by its points: one inside the cell, or none nearer
                        // than the padding and the samples' spacing.
                        const double gap = distance_to_box(s.triangles[refs[i] & kernel::REF_INDEX_MASK], lo, hi);
                        touches = gap == 0.0;
                        near = gap <= 2.0 * std::max({g.pad.x, g.pad.y, g.pad.z}) + kSampleSpacing;
                    }
                    if (touches) {
                        ASSERT_TRUE(listed(cell, i)) << "primitive " << i << " missing from cell " << cell;
                    }
                    if (!near) {
                        ASSERT_FALSE(listed(cell, i)) << "primitive " << i << " listed in far cell " << cell;
                    }
                }
            }
        }
    }
}

TEST(GridBuild, TheGridBoxContainsEveryBoxWithItsPadding) {
    // A ray grazing a primitive on the boundary must still clip to a non-empty
    // interval, so the box leaves at least the padding around every primitive.
    const RandomScene s = random_scene(19, 200, 200);
    std::string note;
    const Grid g = build_grid(s.primitives(), GridRequest{}, note);
    std::vector<Aabb> boxes;
    for (const auto& sp : s.spheres) boxes.push_back(bounds(sp));
    for (const auto& r : s.rings) boxes.push_back(bounds(r));
    for (const auto& c : s.cylinders) boxes.push_back(bounds(c));
    for (const Aabb& b : boxes) {
        EXPECT_TRUE(glm::all(glm::lessThanEqual(g.lo, b.lo - 0.99 * g.pad)));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(g.hi, b.hi + 0.99 * g.pad)));
    }
}

TEST(GridBuild, EachCellListsItsPrimitivesGroupedByKindInTheKernelsOrder) {
    // The kernel walks a cell in one loop per kind, each ending at the first reference
    // of another kind: a cell whose kinds were interleaved would lose primitives.
    const RandomScene s = random_scene(23, 200, 200);
    std::string note;
    const Grid g = build_grid(s.primitives(), GridRequest{}, note);
    std::array<bool, 4> seen{};
    for (std::size_t c = 0; c + 1 < g.nodes.size(); ++c) {   // every leaf, split or not
        if ((g.nodes[c] & kernel::GRID_INNER) != 0) continue;
        const std::uint32_t first = g.nodes[c], end = g.nodes[c + 1] & ~kernel::GRID_INNER;
        for (std::uint32_t i = first; i + 1 < end; ++i) {
            ASSERT_LE(g.refs[i], g.refs[i + 1]) << "cell " << c;  // kind, then index, ascending
        }
        for (std::uint32_t i = first; i < end; ++i) seen[g.refs[i] >> kernel::REF_KIND_SHIFT] = true;
    }
    EXPECT_EQ(seen, (std::array<bool, 4>{true, true, true, true}));
    for (std::uint32_t ref : g.refs) EXPECT_NE(ref, kernel::REF_NONE);
}

TEST(GridBounds, RingBoxIsItsOuterDiscsExactly) {
    // Normal along z: the disc spans the full outer radius in x and y, nothing in z.
    const Aabb flat = bounds(ring({1, 2, 3}, {0, 0, 1}, 0.5f, 2.0f));
    EXPECT_EQ(flat.lo, dvec3(-1, 0, 3));
    EXPECT_EQ(flat.hi, dvec3(3, 4, 3));
    // Normal (0, 0.6, 0.8) as floats, outer 5: half-extents 5 in x, 5 * 0.8 = 4 in y,
    // 5 * 0.6 = 3 in z, up to the floats' rounding of the normal.
    const Aabb tilted = bounds(ring({0, 0, 0}, {0, 3, 4}, 0.0f, 5.0f));
    EXPECT_DOUBLE_EQ(tilted.hi.x, 5.0);
    EXPECT_NEAR(tilted.hi.y, 4.0, 1e-6);
    EXPECT_NEAR(tilted.hi.z, 3.0, 1e-6);
    EXPECT_EQ(tilted.lo, -tilted.hi);
    // The inner radius does not shrink the box: the disc's rim is the annulus's.
    EXPECT_EQ(bounds(ring({0, 0, 0}, {0, 3, 4}, 4.9f, 5.0f)).hi, tilted.hi);
}

TEST(GridBounds, CylinderBoxIsItsEndDiscsUnited) {
    // Along y from (0, 1, 0) to (0, 4, 0), radius 2: discs in the planes y = 1 and y = 4.
    const Aabb up = bounds(cylinder({0, 1, 0}, {0, 4, 0}, 2.0f, false));
    EXPECT_EQ(up.lo, dvec3(-2, 1, -2));
    EXPECT_EQ(up.hi, dvec3(2, 4, 2));
    // Pointing down the axis reversed gives the same box.
    const Aabb down = bounds(cylinder({0, 4, 0}, {0, 1, 0}, 2.0f, true));
    EXPECT_EQ(down.lo, up.lo);
    EXPECT_EQ(down.hi, up.hi);
    // A diagonal in the xy plane: each disc reaches r / sqrt(2) in x and y, r in z.
    const Aabb diag = bounds(cylinder({0, 0, 0}, {3, 3, 0}, 1.0f, false));
    EXPECT_NEAR(diag.lo.x, -std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(diag.hi.y, 3.0 + std::sqrt(0.5), 1e-12);
    EXPECT_DOUBLE_EQ(diag.hi.z, 1.0);
    EXPECT_DOUBLE_EQ(diag.lo.z, -1.0);
}

TEST(GridBuild, RepeatedCoarseningKeepsEveryNoteAndNamesTheLimit) {
    RandomScene s;
    for (int i = 0; i < 30; ++i) {
        const float x = float(i) * 0.01f;
        s.triangles.push_back(triangle({x, 0, 0}, {10, x, 10}, {0, 10, 10 - x}));
    }
    std::string note;
    GridRequest request;
    request.resolution = {64, 64, 64};  // 262,144 cells: over the limit, and far too many copies
    request.max_entries = 10000;
    const Grid g = build_grid(s.primitives(), request, note);
    EXPECT_LE(g.refs.size(), 10000u);
    EXPECT_NE(note.find("exceeds this device's buffer limit of 10000 entries"), std::string::npos) << note;
    // More than one halving, each reported.
    std::size_t halvings = 0;
    for (std::size_t at = note.find("references, over this device's buffer limit of 10000"); at != std::string::npos;
         at = note.find("references, over", at + 1)) {
        ++halvings;
    }
    EXPECT_GE(halvings, 2u) << note;
    expect_exact_binning(g, s);
}

TEST(GridBuild, ReferencesThatCannotFitAreAnErrorNotAHang) {
    RandomScene s = random_scene(5, 40, 0);
    std::string note;
    GridRequest request;
    request.max_entries = 10;  // 60 primitives (40 spheres, 10 rings, 10 cylinders) need 60 references in one cell
    try {
        build_grid(s.primitives(), request, note);
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("60 primitives do not fit one grid: 60 references, over this device's "
                                             "buffer limit of 10 entries"),
                  std::string::npos)
            << e.what();
    }
    request.max_entries = 1;  // not even one cell start beyond the first: still ends
    EXPECT_THROW(build_grid(s.primitives(), request, note), std::runtime_error);
}

TEST(GridBuild, TheHostLimitsCellsWhateverTheDeviceAllows) {
    RandomScene s = random_scene(6, 10, 0);
    std::string note;
    GridRequest request;
    request.resolution = {1024, 1024, 64};  // 2^26 cells
    const Grid g = build_grid(s.primitives(), request, note);
    EXPECT_LE(g.cell_count(), std::uint64_t(1) << 25);
    EXPECT_NE(note.find("exceeds vkrt's limit of 33554432 cells"), std::string::npos) << note;
}

TEST(GridBuild, NonFinitePrimitivesAreRejected) {
    RandomScene s = random_scene(8, 3, 0);
    s.spheres[1].center_radius.y = std::numeric_limits<float>::quiet_NaN();
    std::string note;
    EXPECT_THROW(build_grid(s.primitives(), GridRequest{}, note), std::invalid_argument);
    s = random_scene(8, 0, 3);
    s.triangles[2].p2.z = std::numeric_limits<float>::infinity();
    EXPECT_THROW(build_grid(s.primitives(), GridRequest{}, note), std::invalid_argument);
    s = random_scene(8, 4, 4);
    s.rings[1].normal_outer.w = std::numeric_limits<float>::infinity();
    EXPECT_THROW(build_grid(s.primitives(), GridRequest{}, note), std::invalid_argument);
    s = random_scene(8, 4, 4);
    s.cylinders[0].top_capped.x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(build_grid(s.primitives(), GridRequest{}, note), std::invalid_argument);
}

TEST(GridBuild, NoPrimitivesGivesAnEmptyGrid) {
    std::string note;
    const Grid g = build_grid({}, GridRequest{}, note);
    EXPECT_EQ(g.cell_count(), 1u);
    EXPECT_EQ(g.nodes, (std::vector<std::uint32_t>{0, 0}));
    EXPECT_TRUE(g.refs.empty());
}

// A kind loose as a whole goes first, in index order, into no cell; when every kind
// is loose the grid is one empty cell after them.
TEST(GridBuild, LooseKindsAreListedFirstAndInNoCell) {
    const RandomScene s = random_scene(37, 40, 40);
    GridRequest request;
    request.loose_kinds[kernel::REF_RING] = true;
    request.loose_kinds[kernel::REF_CYLINDER] = true;
    std::string note;
    const Grid g = build_grid(s.primitives(), request, note);
    ASSERT_EQ(g.loose, s.rings.size() + s.cylinders.size());
    for (std::uint32_t i = 0; i < g.loose; ++i) {
        const std::uint32_t kind = i < s.rings.size() ? kernel::REF_RING : kernel::REF_CYLINDER;
        const std::uint32_t index = i < s.rings.size() ? i : i - std::uint32_t(s.rings.size());
        EXPECT_EQ(g.refs[i], (kind << kernel::REF_KIND_SHIFT) | index) << i;
    }
    for (std::size_t i = g.loose; i < g.refs.size(); ++i) {
        const std::uint32_t kind = g.refs[i] >> kernel::REF_KIND_SHIFT;
        ASSERT_TRUE(kind == kernel::REF_SPHERE || kind == kernel::REF_TRIANGLE) << "a loose kind listed in a cell";
    }
    EXPECT_EQ(g.nodes.front(), g.loose);

    request.loose_kinds.fill(true);
    const Grid none = build_grid(s.primitives(), request, note);
    EXPECT_EQ(none.loose, s.size());
    EXPECT_EQ(none.refs.size(), s.size());
    EXPECT_EQ(none.nodes, (std::vector<std::uint32_t>{none.loose, none.loose}));
    EXPECT_TRUE(note.empty()) << note;
}

// A dense cluster in a wide scene, the teapot in a stadium: the builder splits the
// cluster's root cells, and every leaf, at any depth, lists every primitive whose box
// touches its box, and none farther than twice the padding; within a leaf, by kind.
TEST(GridSplit, EveryLeafListsThePrimitivesItOverlaps) {
    std::mt19937 rng(61);
    std::uniform_real_distribution<float> pos(-0.5f, 0.5f);
    std::uniform_real_distribution<float> radius(0.002f, 0.02f);
    RandomScene s;
    for (int i = 0; i < 1500; ++i) s.spheres.push_back(sphere({pos(rng), pos(rng), pos(rng)}, radius(rng)));
    for (int i = 0; i < 40; ++i) {   // a floor 1,000 wide, in strips
        const float x0 = -500.0f + 25.0f * float(i), x1 = x0 + 25.0f;
        s.triangles.push_back(triangle({x0, -1, -500}, {x1, -1, 500}, {x1, -1, -500}));
        s.triangles.push_back(triangle({x0, -1, -500}, {x0, -1, 500}, {x1, -1, 500}));
    }
    std::string note;
    const Grid g = build_grid(s.primitives(), GridRequest{}, note);
    ASSERT_GE(g.levels, 2u) << "the cluster's cells are not split";
    const auto [boxes, refs] = boxes_and_refs(s);
    const dvec3 fine = g.cell / double(kernel::GRID_FINE);
    std::uint64_t leaves = 0;
    std::size_t most = 0;
    // Visits node `node`, whose box starts at fine coordinates `lo` and spans `size` of them.
    std::function<void(std::uint32_t, glm::u64vec3, std::uint64_t)> visit = [&](std::uint32_t node,
                                                                                glm::u64vec3 lo, std::uint64_t size) {
        if ((g.nodes[node] & kernel::GRID_INNER) != 0) {
            ASSERT_GT(size, 1u) << "split below the finest cell";
            ASSERT_EQ(g.nodes[node + 1] & ~kernel::GRID_INNER, (g.nodes[node] & ~kernel::GRID_INNER) + 1)
                << "an inner cell's one reference";
            const std::uint32_t first = g.refs[g.nodes[node] & ~kernel::GRID_INNER];
            const std::uint64_t child = size / 4;
            for (std::uint32_t k = 0; k < kernel::GRID_CHILDREN; ++k) {
                visit(first + k, lo + child * glm::u64vec3(k % 4, k / 4 % 4, k / 16), child);
            }
            return;
        }
        ++leaves;
        const std::vector<std::uint32_t> in = leaf_refs(g, node);
        most = std::max(most, in.size());
        const dvec3 box_lo = g.lo + dvec3(lo) * fine;
        const dvec3 box_hi = box_lo + double(size) * fine;
        ASSERT_TRUE(std::is_sorted(in.begin(), in.end())) << "node " << node;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const Aabb& b = boxes[i];
            const bool listed = std::find(in.begin(), in.end(), refs[i]) != in.end();
            bool touches = glm::all(glm::lessThanEqual(b.lo, box_hi)) && glm::all(glm::lessThanEqual(box_lo, b.hi));
            bool near = glm::all(glm::lessThanEqual(b.lo - 2.0 * g.pad, box_hi)) &&
                        glm::all(glm::lessThanEqual(box_lo, b.hi + 2.0 * g.pad));
            if ((refs[i] >> kernel::REF_KIND_SHIFT) == kernel::REF_TRIANGLE) {
                // The floor's triangles by their polygons (box_overlap_test checks the
                // test against sampled points).
                const kernel::Triangle& t = s.triangles[refs[i] & kernel::REF_INDEX_MASK];
                const std::array<dvec3, 3> v{dvec3(t.p0.x, t.p0.y, t.p0.z), dvec3(t.p1.x, t.p1.y, t.p1.z),
                                             dvec3(t.p2.x, t.p2.y, t.p2.z)};
                touches = polygon_overlaps_box(v, box_lo, box_hi);
                near = polygon_overlaps_box(v, box_lo - 2.0 * g.pad, box_hi + 2.0 * g.pad);
            }
            ASSERT_TRUE(!touches || listed) << "primitive " << i << " missing from node " << node;
            ASSERT_TRUE(near || !listed) << "primitive " << i << " listed in far node " << node;
        }
    };
    const GridResolution& r = g.resolution;
    for (std::uint64_t c = 0; c < g.cell_count(); ++c) {
        const glm::u64vec3 root(c % r[0], c / r[0] % r[1], c / (std::uint64_t(r[0]) * r[1]));
        visit(std::uint32_t(c), root * std::uint64_t(kernel::GRID_FINE), std::uint64_t(kernel::GRID_FINE));
    }
    EXPECT_EQ(leaves, g.leaves);
    EXPECT_LT(most, 100u) << "the cluster's 1,500 spheres still crowd one cell";
}

// A grid whose resolution is given is the uniform grid asked for: never split.
TEST(GridSplit, AGivenResolutionIsNeverSplit) {
    std::mt19937 rng(62);
    std::uniform_real_distribution<float> pos(-0.5f, 0.5f);
    RandomScene s;
    for (int i = 0; i < 1500; ++i) s.spheres.push_back(sphere({pos(rng), pos(rng), pos(rng)}, 0.01f));
    s.spheres.push_back(sphere({900, 0, 0}, 1.0f));
    GridRequest request;
    request.resolution = {8, 8, 8};
    std::string note;
    const Grid g = build_grid(s.primitives(), request, note);
    EXPECT_EQ(g.levels, 0u);
    EXPECT_EQ(g.nodes.size(), 8u * 8 * 8 + 1);
}

}  // namespace
