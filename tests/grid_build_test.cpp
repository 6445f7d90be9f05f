// Grid construction on the host (host/accel/grid.cpp): the resolution heuristic, and
// the flattened arrays: every primitive listed in exactly the cells its padded box
// overlaps, the cell starts a prefix sum of the cell sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <random>
#include <vector>

#include <glm/vector_relational.hpp>

#include "accel/grid.hpp"

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

struct RandomScene {
    std::vector<kernel::Sphere> spheres;
    std::vector<kernel::Triangle> triangles;
};

RandomScene random_scene(std::uint32_t seed, int spheres, int triangles) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f);
    std::uniform_real_distribution<float> size(0.01f, 2.0f);
    RandomScene s;
    for (int i = 0; i < spheres; ++i) s.spheres.push_back(sphere({pos(rng), pos(rng), pos(rng)}, size(rng)));
    for (int i = 0; i < triangles; ++i) {
        const glm::vec3 a(pos(rng), pos(rng), pos(rng));
        const glm::vec3 d1(size(rng), size(rng), -size(rng));
        const glm::vec3 d2(-size(rng), size(rng), size(rng));
        s.triangles.push_back(triangle(a, a + d1, a + d2));
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

// Rebuilds, by brute force over cells, the set of references each cell should hold,
// and compares it with the flattened arrays.
void expect_exact_binning(const Grid& g, const RandomScene& s) {
    const std::uint64_t n = g.cell_count();
    ASSERT_EQ(g.cell_starts.size(), n + 1);
    EXPECT_EQ(g.cell_starts.front(), 0u);
    EXPECT_EQ(g.cell_starts.back(), g.refs.size());
    EXPECT_TRUE(std::is_sorted(g.cell_starts.begin(), g.cell_starts.end())) << "not a prefix sum";

    std::vector<std::vector<std::uint32_t>> want(n);
    auto bin = [&](const Aabb& box, std::uint32_t ref) {
        const auto [first, last] = g.cells_overlapping(box);
        for (std::uint32_t z = 0; z < g.resolution[2]; ++z) {
            for (std::uint32_t y = 0; y < g.resolution[1]; ++y) {
                for (std::uint32_t x = 0; x < g.resolution[0]; ++x) {
                    const bool inside = x >= first[0] && x <= last[0] && y >= first[1] && y <= last[1] &&
                                        z >= first[2] && z <= last[2];
                    if (inside) want[(std::uint64_t(z) * g.resolution[1] + y) * g.resolution[0] + x].push_back(ref);
                }
            }
        }
    };
    for (std::uint32_t i = 0; i < s.spheres.size(); ++i) {
        bin(bounds(s.spheres[i]), (kernel::REF_SPHERE << kernel::REF_KIND_SHIFT) | i);
    }
    for (std::uint32_t i = 0; i < s.triangles.size(); ++i) {
        bin(bounds(s.triangles[i]), (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | i);
    }
    for (std::uint64_t c = 0; c < n; ++c) {
        const std::vector<std::uint32_t> got(g.refs.begin() + g.cell_starts[c], g.refs.begin() + g.cell_starts[c + 1]);
        ASSERT_EQ(got, want[c]) << "cell " << c;
    }
}

TEST(GridBuild, EveryPrimitiveIsInExactlyTheCellsItsBoxOverlaps) {
    const RandomScene s = random_scene(7, 300, 200);
    std::string note;
    const Grid g = build_grid(s.spheres, s.triangles, GridRequest{}, note);
    EXPECT_TRUE(note.empty()) << note;
    EXPECT_GT(cells(g.resolution), 1000u);
    expect_exact_binning(g, s);
}

TEST(GridBuild, CellsCoverEveryBoxWithPadding) {
    // The padded overlap really covers each box: its corners fall into the listed
    // cells by the same arithmetic the kernel uses for a point.
    const RandomScene s = random_scene(11, 500, 0);
    std::string note;
    const Grid g = build_grid(s.spheres, s.triangles, GridRequest{}, note);
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
    const Grid g = build_grid(s.spheres, s.triangles, request, note);
    EXPECT_EQ(g.resolution, (GridResolution{3, 4, 5}));
    EXPECT_TRUE(note.empty());
    expect_exact_binning(g, s);

    request.resolution = {100, 100, 100};
    request.max_entries = 20001;  // 20,000 cells at most
    const Grid clamped = build_grid(s.spheres, s.triangles, request, note);
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
    const Grid g = build_grid(s.spheres, s.triangles, request, note);
    EXPECT_LE(g.refs.size(), 40000u);
    EXPECT_LT(g.cell_count(), 32000u);
    EXPECT_NE(note.find("references"), std::string::npos) << note;
    expect_exact_binning(g, s);
}

TEST(GridBuild, FlatSceneAndSinglePrimitive) {
    // All triangles in the plane z = 0: the grid still has positive cell sizes.
    RandomScene flat;
    for (int i = 0; i < 100; ++i) {
        const float x = float(i % 10), y = float(i / 10);
        flat.triangles.push_back(triangle({x, y, 0}, {x + 1, y, 0}, {x, y + 1, 0}));
    }
    std::string note;
    const Grid g = build_grid(flat.spheres, flat.triangles, GridRequest{}, note);
    EXPECT_EQ(g.resolution[2], 1u);
    EXPECT_GT(g.cell[2], 0.0);
    expect_exact_binning(g, flat);

    RandomScene one;
    one.spheres.push_back(sphere({1e5f, -1e5f, 3.0f}, 0.5f));
    const Grid single = build_grid(one.spheres, one.triangles, GridRequest{}, note);
    EXPECT_GE(single.cell_count(), 1u);
    expect_exact_binning(single, one);
}

TEST(GridBuild, CellsListedAreThoseTheBoxTouchesByGeometry) {
    // Independent of cells_overlapping: a cell must hold a primitive when the cell's
    // slab intersects the primitive's box on every axis, and may hold it only when it
    // intersects the box grown by twice the padding.
    const RandomScene s = random_scene(13, 120, 80);
    std::string note;
    const Grid g = build_grid(s.spheres, s.triangles, GridRequest{}, note);
    std::vector<Aabb> boxes;
    for (const auto& sp : s.spheres) boxes.push_back(bounds(sp));
    for (const auto& t : s.triangles) boxes.push_back(bounds(t));
    auto listed = [&](std::uint64_t cell, std::uint32_t i) {
        const std::uint32_t ref = i < s.spheres.size()
                                      ? (kernel::REF_SPHERE << kernel::REF_KIND_SHIFT) | i
                                      : (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | std::uint32_t(i - s.spheres.size());
        return std::find(g.refs.begin() + g.cell_starts[cell], g.refs.begin() + g.cell_starts[cell + 1], ref) !=
               g.refs.begin() + g.cell_starts[cell + 1];
    };
    for (std::uint32_t z = 0; z < g.resolution[2]; ++z) {
        for (std::uint32_t y = 0; y < g.resolution[1]; ++y) {
            for (std::uint32_t x = 0; x < g.resolution[0]; ++x) {
                const dvec3 lo = g.lo + g.cell * dvec3(x, y, z);
                const dvec3 hi = lo + g.cell;
                const std::uint64_t cell = (std::uint64_t(z) * g.resolution[1] + y) * g.resolution[0] + x;
                for (std::uint32_t i = 0; i < boxes.size(); ++i) {
                    const Aabb& b = boxes[i];
                    const bool touches = glm::all(glm::lessThanEqual(b.lo, hi)) && glm::all(glm::lessThanEqual(lo, b.hi));
                    const bool near = glm::all(glm::lessThanEqual(b.lo - 2.0 * g.pad, hi)) &&
                                      glm::all(glm::lessThanEqual(lo, b.hi + 2.0 * g.pad));
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
    const Grid g = build_grid(s.spheres, s.triangles, GridRequest{}, note);
    for (const auto& sp : s.spheres) {
        const Aabb b = bounds(sp);
        EXPECT_TRUE(glm::all(glm::lessThanEqual(g.lo, b.lo - 0.99 * g.pad)));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(g.hi, b.hi + 0.99 * g.pad)));
    }
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
    const Grid g = build_grid(s.spheres, s.triangles, request, note);
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
    request.max_entries = 10;  // 40 primitives need 40 references even in one cell
    try {
        build_grid(s.spheres, s.triangles, request, note);
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("40 primitives do not fit one grid: 40 references, over this device's "
                                             "buffer limit of 10 entries"),
                  std::string::npos)
            << e.what();
    }
    request.max_entries = 1;  // not even one cell start beyond the first: still ends
    EXPECT_THROW(build_grid(s.spheres, s.triangles, request, note), std::runtime_error);
}

TEST(GridBuild, TheHostLimitsCellsWhateverTheDeviceAllows) {
    RandomScene s = random_scene(6, 10, 0);
    std::string note;
    GridRequest request;
    request.resolution = {1024, 1024, 64};  // 2^26 cells
    const Grid g = build_grid(s.spheres, s.triangles, request, note);
    EXPECT_LE(g.cell_count(), std::uint64_t(1) << 25);
    EXPECT_NE(note.find("exceeds vkrt's limit of 33554432 cells"), std::string::npos) << note;
}

TEST(GridBuild, NonFinitePrimitivesAreRejected) {
    RandomScene s = random_scene(8, 3, 0);
    s.spheres[1].center_radius.y = std::numeric_limits<float>::quiet_NaN();
    std::string note;
    EXPECT_THROW(build_grid(s.spheres, s.triangles, GridRequest{}, note), std::invalid_argument);
    s = random_scene(8, 0, 3);
    s.triangles[2].p2.z = std::numeric_limits<float>::infinity();
    EXPECT_THROW(build_grid(s.spheres, s.triangles, GridRequest{}, note), std::invalid_argument);
}

TEST(GridBuild, NoPrimitivesGivesAnEmptyGrid) {
    std::string note;
    const Grid g = build_grid({}, {}, GridRequest{}, note);
    EXPECT_EQ(g.cell_count(), 1u);
    EXPECT_EQ(g.cell_starts, (std::vector<std::uint32_t>{0, 0}));
    EXPECT_TRUE(g.refs.empty());
}

}  // namespace
