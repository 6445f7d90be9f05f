// The separating-axis test that bins triangles and quads into the cells they cross
// (host/accel/box_overlap.cpp), on cases whose answer is known by construction.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "accel/box_overlap.hpp"

namespace {

using glm::dvec3;
using vkrt::polygon_overlaps_box;

const dvec3 kLo(0.0), kHi(1.0);   // the unit box

bool overlaps(std::vector<dvec3> v) { return polygon_overlaps_box(v, kLo, kHi); }

TEST(BoxOverlap, TriangleThroughTheBoxOverlaps) {
    EXPECT_TRUE(overlaps({{-1, 0.5, 0.5}, {2, 0.5, 0.5}, {0.5, 2, 0.5}}));
    // Larger than the box on every side, cutting it in its middle plane.
    EXPECT_TRUE(overlaps({{-10, -10, 0.5}, {10, -10, 0.5}, {0, 10, 0.5}}));
    // Wholly inside.
    EXPECT_TRUE(overlaps({{0.2, 0.2, 0.2}, {0.3, 0.2, 0.2}, {0.2, 0.3, 0.2}}));
}

TEST(BoxOverlap, TriangleWhoseBoxOverlapsButWhichPassesTheCornerMisses) {
    // The plane x + y + z = 3.5 passes beyond the corner (1, 1, 1), whose sum is 3,
    // while the triangle's box [0, 3.5]^3 holds the whole unit box.
    EXPECT_FALSE(overlaps({{3.5, 0, 0}, {0, 3.5, 0}, {0, 0, 3.5}}));
    // At x + y + z = 3 it touches the corner: closed boxes share the point.
    EXPECT_TRUE(overlaps({{3, 0, 0}, {0, 3, 0}, {0, 0, 3}}));
    EXPECT_TRUE(overlaps({{2.9, 0, 0}, {0, 2.9, 0}, {0, 0, 2.9}}));
}

TEST(BoxOverlap, ThinTriangleAlongTheDiagonalMissesTheOffDiagonalCells) {
    // A sliver from (0, 0) to (4, 4) in z = 0.5, its lower edge of slope 0.9975,
    // across a 4 x 4 square of unit cells, all of which its box covers.
    const std::vector<dvec3> sliver{{0, 0, 0.5}, {4, 4, 0.5}, {4, 3.99, 0.5}};
    int crossed = 0;
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            const dvec3 lo(x, y, 0.0);
            const bool hit = polygon_overlaps_box(sliver, lo, lo + dvec3(1.0));
            crossed += hit;
            EXPECT_EQ(hit, std::abs(x - y) <= 1) << x << ", " << y;
        }
    }
    // The diagonal's 4, the 3 below it that the lower edge enters at their left
    // faces, and the 3 above it that the diagonal touches at a corner (the boxes are
    // closed).
    EXPECT_EQ(crossed, 10);
}

TEST(BoxOverlap, EdgeAxesSeparateWhatTheFaceAxesCannot) {
    // Triangles in the plane y = 0.5, which crosses the box, whose boxes overlap the
    // box's: only an edge crossed with the y axis can tell them apart. In x and z:
    // (2, -1), (2, 2), (-1, 2) holds the points with x + z >= 1, such as (1, 1).
    EXPECT_TRUE(overlaps({{2, 0.5, -1}, {2, 0.5, 2}, {-1, 0.5, 2}}));
    // (3.5, -1), (3.5, 3.5), (-1, 3.5) holds only x + z >= 2.5; the box's square
    // reaches 2.
    EXPECT_FALSE(overlaps({{3.5, 0.5, -1}, {3.5, 0.5, 3.5}, {-1, 0.5, 3.5}}));
}

TEST(BoxOverlap, QuadsAreTestedWithTheirFourthVertex) {
    // The parallelogram p0, p1, p2, p0 + p2 - p1 in z = 0.5: corners (3, 0.5),
    // (3, 3), (0.5, 3) and (0.5, 0.5), the square [0.5, 3]^2. The triangle of its
    // first three vertices holds only x + y >= 3.5 and misses the box; the square
    // overlaps it on [0.5, 1]^2.
    const std::vector<dvec3> square{{3, 0.5, 0.5}, {3, 3, 0.5}, {0.5, 3, 0.5}, {0.5, 0.5, 0.5}};
    EXPECT_FALSE(overlaps({square[0], square[1], square[2]}));
    EXPECT_TRUE(overlaps(square));
    // The square [1.5, 3]^2 misses.
    EXPECT_FALSE(overlaps({{3, 1.5, 0.5}, {3, 3, 0.5}, {1.5, 3, 0.5}, {1.5, 1.5, 0.5}}));
}

TEST(BoxOverlap, DegenerateTrianglesAreTheirSegments) {
    // Collinear vertices: a segment through the box, and one passing by its edge.
    EXPECT_TRUE(overlaps({{-1, -1, -1}, {0.5, 0.5, 0.5}, {2, 2, 2}}));
    EXPECT_FALSE(overlaps({{-1, 1.5, 0.5}, {0.0, 1.5, 1.5}, {1.0, 1.5, 2.5}}));
    // A diagonal segment in z = 0.5 that passes the corner (1, 1) at x + y = 2.2.
    EXPECT_FALSE(overlaps({{2.2, 0, 0.5}, {1.1, 1.1, 0.5}, {0, 2.2, 0.5}}));
    // All three vertices at one point.
    EXPECT_TRUE(overlaps({{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}}));
    EXPECT_FALSE(overlaps({{1.5, 0.5, 0.5}, {1.5, 0.5, 0.5}, {1.5, 0.5, 0.5}}));
}

// A point of the triangle, by barycentric coordinates.
dvec3 at(const std::array<dvec3, 3>& t, double u, double v) { return t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]); }

TEST(BoxOverlap, AgreesWithDenseSamplesOnRandomTriangles) {
    // Independent of the axes: a triangle overlaps when one of its sampled points is
    // inside the box, and cannot when every sample is farther than the sampling step.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> pos(-1.5, 2.5);
    constexpr int kSteps = 64;
    int inside = 0, apart = 0;
    for (int n = 0; n < 2000; ++n) {
        const std::array<dvec3, 3> t{dvec3(pos(rng), pos(rng), pos(rng)), dvec3(pos(rng), pos(rng), pos(rng)),
                                     dvec3(pos(rng), pos(rng), pos(rng))};
        const double step = std::max({glm::length(t[1] - t[0]), glm::length(t[2] - t[0]), glm::length(t[2] - t[1])}) /
                            kSteps;
        bool any_inside = false;
        double nearest = 1e30;
        for (int i = 0; i <= kSteps; ++i) {
            for (int j = 0; i + j <= kSteps; ++j) {
                const dvec3 p = at(t, double(i) / kSteps, double(j) / kSteps);
                const dvec3 d = glm::max(glm::max(kLo - p, p - kHi), dvec3(0.0));
                nearest = std::min(nearest, glm::length(d));
                any_inside = any_inside || nearest == 0.0;
            }
        }
        const bool got = overlaps({t[0], t[1], t[2]});
        if (any_inside) {
            EXPECT_TRUE(got) << "triangle " << n;
            ++inside;
        }
        if (nearest > step) {
            EXPECT_FALSE(got) << "triangle " << n;
            ++apart;
        }
    }
    EXPECT_GT(inside, 200);
    EXPECT_GT(apart, 200);
}

}  // namespace
