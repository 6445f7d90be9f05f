// Placing the grid's cells (host/accel/grid_split.cpp) on grids small enough to
// lay out by hand: which cells a primitive is binned into (a polygon only where it
// crosses them), the node and reference layout of a uniform grid, and when a
// crowded cell is split into 4 x 4 x 4 children: only where the surface-area
// argument says it pays, the grid is crowded, and the limits on references and
// node words leave room.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "accel/grid.hpp"
#include "accel/grid_split.hpp"

namespace {

using namespace vkrt;
using glm::dvec3;
using Cell = std::array<std::uint32_t, 3>;

std::uint32_t sphere_ref(std::uint32_t index) { return kernel::REF_SPHERE << kernel::REF_KIND_SHIFT | index; }
std::uint32_t triangle_ref(std::uint32_t index) { return kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT | index; }

kernel::Triangle triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, std::uint32_t shape = kernel::SHAPE_TRIANGLE) {
    kernel::Triangle t{};
    t.p0 = kernel::vec4(a, 0.0f);
    t.p1 = kernel::vec4(b, 0.0f);
    t.p2 = kernel::vec4(c, 0.0f);
    t.meta.z = shape;
    return t;
}

// The cells Binner::cells calls back with, in its order.
std::vector<Cell> binned(const Binner& binner, const Aabb& box, std::uint32_t id, const GridResolution& res) {
    std::vector<Cell> cells;
    binner.cells(box, id, dvec3(0.0), dvec3(1.0), dvec3(0.01), res,
                 [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) { cells.push_back({x, y, z}); });
    return cells;
}

TEST(Binner, ABoxGoesIntoEveryCellItsPaddedBoxOverlaps) {
    const Binner binner{};
    const Aabb box{dvec3(0.2, 0.3, 0.3), dvec3(1.8, 0.7, 0.7)};
    EXPECT_EQ(binned(binner, box, sphere_ref(0), {4, 4, 4}), (std::vector<Cell>{{0, 0, 0}, {1, 0, 0}}));
    // Within the padding of the next cell: in it too.
    const Aabb reaching{dvec3(0.2, 0.3, 0.3), dvec3(1.995, 0.7, 0.7)};
    EXPECT_EQ(binned(binner, reaching, sphere_ref(0), {4, 4, 4}),
              (std::vector<Cell>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}));
    // Clamped into the grid.
    const Aabb beyond{dvec3(-5.0, 0.3, 0.3), dvec3(0.5, 0.7, 0.7)};
    EXPECT_EQ(binned(binner, beyond, sphere_ref(0), {4, 4, 4}), (std::vector<Cell>{{0, 0, 0}}));
}

TEST(Binner, APolygonGoesOnlyIntoTheCellsItCrosses) {
    // A right triangle in the plane z = 0.5 with its hypotenuse on x + y = 3.5: of
    // the 4 x 4 cells its box covers, those with x + y <= 3 (10 of them).
    const std::vector<kernel::Triangle> triangles{
        triangle({0.1f, 0.1f, 0.5f}, {3.4f, 0.1f, 0.5f}, {0.1f, 3.4f, 0.5f})};
    const Binner binner{triangles};
    const Aabb box{dvec3(0.1, 0.1, 0.5), dvec3(3.4, 3.4, 0.5)};
    std::vector<Cell> expected;
    for (std::uint32_t y = 0; y < 4; ++y) {
        for (std::uint32_t x = 0; x < 4; ++x) {
            if (x + y <= 3) expected.push_back({x, y, 0});
        }
    }
    EXPECT_EQ(binned(binner, box, triangle_ref(0), {4, 4, 1}), expected);
    // The same box as any other kind's: all 16.
    EXPECT_EQ(binned(binner, box, sphere_ref(0), {4, 4, 1}).size(), 16u);
}

TEST(Binner, PolygonsAreTrianglesAndQuads) {
    const std::vector<kernel::Triangle> triangles{
        triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}),
        triangle({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, kernel::SHAPE_PARALLELOGRAM)};
    const Binner binner{triangles};
    std::array<dvec3, 4> v;
    ASSERT_EQ(binner.polygon(triangle_ref(0), v), 3u);
    EXPECT_EQ(v[1], dvec3(1, 0, 0));
    // A quad's fourth corner is p0 + (p2 - p1), as the kernel computes it.
    ASSERT_EQ(binner.polygon(triangle_ref(1), v), 4u);
    EXPECT_EQ(v[3], dvec3(0, 1, 0));
    EXPECT_EQ(binner.polygon(sphere_ref(1), v), 0u);
}

// A grid of `res` root cells of side `side` from the origin, with the references
// `loose` outside every cell.
Grid empty_grid(const GridResolution& res, double side, std::vector<std::uint32_t> loose = {}) {
    Grid g;
    g.lo = dvec3(0.0);
    g.cell = dvec3(side);
    g.resolution = res;
    g.hi = dvec3(res[0], res[1], res[2]) * side;
    g.loose = std::uint32_t(loose.size());
    g.refs = std::move(loose);
    return g;
}

// Primitives given as boxes, all spheres; root cells listed by hand.
struct Placement {
    std::vector<Aabb> boxes;
    std::vector<std::uint32_t> ids;
    RootCells roots;

    void add_sphere(dvec3 centre, double radius) {
        boxes.push_back({centre - radius, centre + radius});
        ids.push_back(sphere_ref(std::uint32_t(ids.size())));
    }
    void place(Grid& g, bool split, std::uint64_t max_refs = 1u << 30, std::uint64_t max_words = 1u << 30) const {
        place_cells(g, roots, boxes, ids, Binner{}, std::vector<double>(boxes.size(), 0.0), split, max_refs,
                    max_words);
    }
};

TEST(PlaceCells, AUniformGridIsAPrefixSumAfterTheLooseReferences) {
    Placement p;
    for (int i = 0; i < 3; ++i) p.add_sphere(dvec3(0.5), 0.1);  // the boxes matter only for splits
    // Root cells 0 to 3 hold {0}, {0, 1}, {} and {2}.
    p.roots.starts = {0, 1, 3, 3, 4};
    p.roots.items = {0, 0, 1, 2};
    const std::uint32_t loose = sphere_ref(7);
    Grid g = empty_grid({4, 1, 1}, 1.0, {loose});
    p.place(g, true);
    EXPECT_EQ(g.nodes, (std::vector<std::uint32_t>{1, 2, 4, 4, 5}));
    EXPECT_EQ(g.refs, (std::vector<std::uint32_t>{loose, p.ids[0], p.ids[0], p.ids[1], p.ids[2]}));
    EXPECT_EQ(g.leaves, 4u);
    EXPECT_EQ(g.levels, 0u);
}

// One root cell of side 4 holding 64 small spheres, one at the centre of each of
// its children (listed in child order: x fastest, then y, then z).
Placement one_per_child() {
    Placement p;
    for (std::uint32_t k = 0; k < kernel::GRID_CHILDREN; ++k) {
        p.add_sphere(dvec3(k % 4, k / 4 % 4, k / 16) + 0.5, 0.1);
        p.roots.items.push_back(k);
    }
    p.roots.starts = {0, kernel::GRID_CHILDREN};
    return p;
}

TEST(PlaceCells, ACrowdedCellSplitsIntoItsChildren) {
    const Placement p = one_per_child();
    Grid g = empty_grid({1, 1, 1}, 4.0);
    p.place(g, true);
    // The root is an inner cell: its reference is its first child's node, 1. Each
    // child is a leaf holding its sphere; the last word is the end of the references.
    ASSERT_EQ(g.nodes.size(), 1u + kernel::GRID_CHILDREN + 1u);
    EXPECT_EQ(g.nodes[0], kernel::GRID_INNER | 0u);
    ASSERT_EQ(g.refs.size(), 1u + kernel::GRID_CHILDREN);
    EXPECT_EQ(g.refs[0], 1u);
    for (std::uint32_t k = 0; k < kernel::GRID_CHILDREN; ++k) {
        EXPECT_EQ(g.nodes[1 + k], 1 + k) << "child " << k;
        EXPECT_EQ(g.refs[1 + k], p.ids[k]) << "child " << k;
    }
    EXPECT_EQ(g.nodes.back(), 1u + kernel::GRID_CHILDREN);
    EXPECT_EQ(g.levels, 1u);
    EXPECT_EQ(g.leaves, kernel::GRID_CHILDREN);
}

// The same cell left whole: one leaf of all 64 references.
void expect_unsplit(const Grid& g, const Placement& p) {
    EXPECT_EQ(g.levels, 0u);
    EXPECT_EQ(g.nodes, (std::vector<std::uint32_t>{0, kernel::GRID_CHILDREN}));
    EXPECT_EQ(g.refs, p.ids);
}

TEST(PlaceCells, NoSplitWithoutRoomOrWhenAskedNot) {
    const Placement p = one_per_child();
    const auto placed = [&](bool split, std::uint64_t max_refs, std::uint64_t max_words) {
        Grid g = empty_grid({1, 1, 1}, 4.0);
        p.place(g, split, max_refs, max_words);
        return g;
    };
    constexpr std::uint64_t kAny = 1u << 30;
    expect_unsplit(placed(false, kAny, kAny), p);
    // The split needs one reference more (the inner cell's) and 64 node words more.
    expect_unsplit(placed(true, kernel::GRID_CHILDREN, kAny), p);
    expect_unsplit(placed(true, kAny, 1 + kernel::GRID_CHILDREN), p);
    EXPECT_EQ(placed(true, kernel::GRID_CHILDREN + 1, 1 + kernel::GRID_CHILDREN + 1).levels, 1u)
        << "exactly enough room";
}

TEST(PlaceCells, NoSplitWhereItWouldNotPay) {
    // Spheres that each fill the whole cell would be listed in every child.
    Placement p;
    for (std::uint32_t k = 0; k < kernel::GRID_CHILDREN; ++k) {
        p.add_sphere(dvec3(2.0), 2.0);
        p.roots.items.push_back(k);
    }
    p.roots.starts = {0, kernel::GRID_CHILDREN};
    Grid g = empty_grid({1, 1, 1}, 4.0);
    p.place(g, true);
    expect_unsplit(g, p);
}

TEST(PlaceCells, NoSplitInAGridThatIsNotCrowded) {
    // 20 spheres in one cell would pay to split (10 + 20 / 16 tests against 20),
    // but a grid is crowded only where a primitive shares its cell with 64 others
    // on average.
    Placement p;
    for (std::uint32_t k = 0; k < 20; ++k) {
        p.add_sphere(dvec3(k % 4, k / 4 % 4, k / 16) + 0.5, 0.1);
        p.roots.items.push_back(k);
    }
    p.roots.starts = {0, 20};
    Grid g = empty_grid({1, 1, 1}, 4.0);
    p.place(g, true);
    EXPECT_EQ(g.levels, 0u);
    EXPECT_EQ(g.refs, p.ids);
}

}  // namespace
