// Rings and cylinders in the kernel (shaders/kernel/shapes/ring.glsl, cylinder.glsl),
// through the reference backend's view of the shared GLSL. As in
// intersect_test.cpp the inputs are chosen so that every intermediate is exact
// in float (axis-aligned axes and normals, small whole and half coordinates), so the
// expected t values and normals, worked out by hand in the comments, are checked for
// equality. Where a case cannot be exact, the expected value is computed in double and
// the check allows a few float roundings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "kernel/kernel.hpp"

namespace {

namespace kernel = vkrt::kernel;
using kernel::CYLINDER_BASE_CAP;
using kernel::CYLINDER_SIDE;
using kernel::CYLINDER_TOP_CAP;
using kernel::INFINITY_T;
using kernel::Kernel;
using kernel::uvec4;
using kernel::vec3;
using kernel::vec4;

Kernel::Ray ray(vec3 origin, vec3 dir) { return Kernel::Ray(origin, dir); }

::testing::AssertionResult same(const vec3& got, const vec3& want) {
    if (got == want) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got (" << got.x << ", " << got.y << ", " << got.z << "), want ("
                                         << want.x << ", " << want.y << ", " << want.z << ")";
}

// ---- rings: intersect_ring -----------------------------------------------------------

// The ring of the tests: around the origin in the plane z = 0, front face +z, the
// points at distance 1 to 2 from the centre.
const vec3 kRingCenter(0, 0, 0);
const vec3 kRingNormal(0, 0, 1);

float ring_t(const Kernel::Ray& r, float t_max = INFINITY_T) {
    return Kernel{}.intersect_ring(r, kRingCenter, kRingNormal, 1.0f, 2.0f, 0.0f, t_max);
}

TEST(RingIntersect, HitsTheAnnulusFromTheFront) {
    // Straight down from z = 5 at distance 1.5 from the centre: t = 5.
    EXPECT_EQ(ring_t(ray(vec3(1.5f, 0, 5), vec3(0, 0, -1))), 5.0f);
    // Off every axis: (0.5, 1.25) lies at distance^2 0.25 + 1.5625 = 1.8125, inside [1, 4].
    EXPECT_EQ(ring_t(ray(vec3(0.5f, 1.25f, 2), vec3(0, 0, -1))), 2.0f);
}

TEST(RingIntersect, HitsTheBackFaceToo) {
    EXPECT_EQ(ring_t(ray(vec3(0, -1.5f, -3), vec3(0, 0, 1))), 3.0f);
}

TEST(RingIntersect, TheHoleAndBeyondTheOuterRadiusMiss) {
    EXPECT_EQ(ring_t(ray(vec3(0.5f, 0, 5), vec3(0, 0, -1))), INFINITY_T);   // in the hole
    EXPECT_EQ(ring_t(ray(vec3(0, 0, 5), vec3(0, 0, -1))), INFINITY_T);      // through the centre
    EXPECT_EQ(ring_t(ray(vec3(2.5f, 0, 5), vec3(0, 0, -1))), INFINITY_T);   // beyond the outer radius
    EXPECT_EQ(ring_t(ray(vec3(1.5f, 1.5f, 5), vec3(0, 0, -1))), INFINITY_T);  // distance^2 4.5 > 4
}

TEST(RingIntersect, BothRadiiAreInside) {
    // The annulus is closed: distance exactly 1 or exactly 2 is a hit.
    EXPECT_EQ(ring_t(ray(vec3(1, 0, 5), vec3(0, 0, -1))), 5.0f);
    EXPECT_EQ(ring_t(ray(vec3(0, -2, 5), vec3(0, 0, -1))), 5.0f);
    // One float step inside the hole, or outside the rim, misses.
    EXPECT_EQ(ring_t(ray(vec3(std::nextafter(1.0f, 0.0f), 0, 5), vec3(0, 0, -1))), INFINITY_T);
    EXPECT_EQ(ring_t(ray(vec3(0, std::nextafter(-2.0f, -3.0f), 5), vec3(0, 0, -1))), INFINITY_T);
}

TEST(RingIntersect, ARayParallelToThePlaneMisses) {
    // Above the plane, and in it: either way the denominator is 0.
    EXPECT_EQ(ring_t(ray(vec3(-5, 1.5f, 1), vec3(1, 0, 0))), INFINITY_T);
    EXPECT_EQ(ring_t(ray(vec3(-5, 1.5f, 0), vec3(1, 0, 0))), INFINITY_T);
}

TEST(RingIntersect, RespectsTheIntervalAndWhatIsBehind) {
    const auto down = ray(vec3(1.5f, 0, 5), vec3(0, 0, -1));
    EXPECT_EQ(ring_t(down, 5.0f), INFINITY_T);  // t_max is exclusive
    EXPECT_EQ(ring_t(ray(vec3(1.5f, 0, 5), vec3(0, 0, 1))), INFINITY_T);  // ring behind the origin
}

TEST(RingIntersect, AnOffsetTiltedRing) {
    // Centre (1, 2, 3), normal +y: the plane y = 2. From (2.5, 7, 3) down: t = 5,
    // landing at distance 1.5 from the centre.
    Kernel k;
    EXPECT_EQ(k.intersect_ring(ray(vec3(2.5f, 7, 3), vec3(0, -1, 0)), vec3(1, 2, 3), vec3(0, 1, 0), 1.0f, 2.0f, 0.0f,
                               INFINITY_T),
              5.0f);
    // Normal (0, 0.6, 0.8) (a 3-4-5 tilt), a disc of radius 1 at the origin, the ray
    // along -z from (0, 0, 10): t = 10 exactly (the plane passes through the origin).
    const vec3 n = glm::normalize(vec3(0, 3, 4));
    EXPECT_EQ(k.intersect_ring(ray(vec3(0, 0, 10), vec3(0, 0, -1)), vec3(0), n, 0.0f, 1.0f, 0.0f, INFINITY_T), 10.0f);
    // From (0, 1, 10) the plane 0.6 y + 0.8 z = 0 is met at z = -0.75, t = 10.75; the
    // point (0, 1, -0.75) lies 1.25 from the centre: inside a disc of 1.5, not of 1.2.
    EXPECT_FLOAT_EQ(k.intersect_ring(ray(vec3(0, 1, 10), vec3(0, 0, -1)), vec3(0), n, 0.0f, 1.5f, 0.0f, INFINITY_T),
                    10.75f);
    EXPECT_EQ(k.intersect_ring(ray(vec3(0, 1, 10), vec3(0, 0, -1)), vec3(0), n, 0.0f, 1.2f, 0.0f, INFINITY_T),
              INFINITY_T);
}

// ---- cylinders: intersect_cylinder --------------------------------------------------

// The cylinder of the tests: radius 1 around the y axis from y = 0 to y = 4.
const vec3 kBase(0, 0, 0);
const vec3 kTop(0, 4, 0);

Kernel::CylinderHit cyl(const Kernel::Ray& r, bool capped, float t_max = INFINITY_T) {
    return Kernel{}.intersect_cylinder(r, kBase, kTop, 1.0f, capped, 0.0f, t_max);
}

TEST(CylinderIntersect, SideFromOutside) {
    // From (-5, 1, 0) along +x: o_perp = (-5, 0, 0), d_perp = (1, 0, 0), A = 1, B = -5,
    // f = 0, disc = 1, C = 24, q = 1 + 5 = 6: roots 6 and 24 / 6 = 4. Height 1.
    for (bool capped : {false, true}) {
        const auto h = cyl(ray(vec3(-5, 1, 0), vec3(1, 0, 0)), capped);
        EXPECT_EQ(h.t, 4.0f);
        EXPECT_EQ(h.part, CYLINDER_SIDE);
    }
    // Off the axis's plane: from (-5, 2, 0.6) the chord's half is 0.8 (0.6^2 + 0.8^2 =
    // 1), so the side is met at x = -0.8, t = 4.2.
    const auto h = cyl(ray(vec3(-5, 2, 0.6f), vec3(1, 0, 0)), false);
    EXPECT_FLOAT_EQ(h.t, 4.2f);
    EXPECT_EQ(h.part, CYLINDER_SIDE);
}

TEST(CylinderIntersect, FromInsideAnOpenCylinderTheFarWall) {
    // From the axis at height 1 along +x: roots -1 and 1; the near one is behind.
    const auto h = cyl(ray(vec3(0, 1, 0), vec3(1, 0, 0)), false);
    EXPECT_EQ(h.t, 1.0f);
    EXPECT_EQ(h.part, CYLINDER_SIDE);
    // Off the axis: from (0.5, 3, 0) along -x the wall is 1.5 away.
    EXPECT_EQ(cyl(ray(vec3(0.5f, 3, 0), vec3(-1, 0, 0)), false).t, 1.5f);
}

TEST(CylinderIntersect, FromInsideACappedCylinderTheCapOrTheWall) {
    // Up from (0.5, 1, 0): the side is parallel, the top cap 3 away.
    auto h = cyl(ray(vec3(0.5f, 1, 0), vec3(0, 1, 0)), true);
    EXPECT_EQ(h.t, 3.0f);
    EXPECT_EQ(h.part, CYLINDER_TOP_CAP);
    // Down from the same point: the base cap, 1 away.
    h = cyl(ray(vec3(0.5f, 1, 0), vec3(0, -1, 0)), true);
    EXPECT_EQ(h.t, 1.0f);
    EXPECT_EQ(h.part, CYLINDER_BASE_CAP);
    // Sideways the wall comes first; no cap is on the way.
    h = cyl(ray(vec3(0, 1, 0), vec3(1, 0, 0)), true);
    EXPECT_EQ(h.t, 1.0f);
    EXPECT_EQ(h.part, CYLINDER_SIDE);
    // Obliquely up (0.6, 0.8, 0) from (0, 3, 0): the top cap at t = 1 / 0.8 = 1.25,
    // where x = 0.75 (inside the disc), before the wall at t = 1 / 0.6.
    h = cyl(ray(vec3(0, 3, 0), glm::normalize(vec3(3, 4, 0))), true);
    EXPECT_FLOAT_EQ(h.t, 1.25f);
    EXPECT_EQ(h.part, CYLINDER_TOP_CAP);
    // Open, the same ray leaves through the top: the wall's height there is
    // 3 + 0.8 / 0.6 > 4, so it misses.
    EXPECT_EQ(cyl(ray(vec3(0, 3, 0), glm::normalize(vec3(3, 4, 0))), false).t, INFINITY_T);
}

TEST(CylinderIntersect, CapsFromOutside) {
    // Straight down onto the top cap at (0.5, 4, 0.25): t = 6; the base cap (t = 10)
    // is behind it.
    auto h = cyl(ray(vec3(0.5f, 10, 0.25f), vec3(0, -1, 0)), true);
    EXPECT_EQ(h.t, 6.0f);
    EXPECT_EQ(h.part, CYLINDER_TOP_CAP);
    // Straight up onto the base cap.
    h = cyl(ray(vec3(-0.5f, -2, 0), vec3(0, 1, 0)), true);
    EXPECT_EQ(h.t, 2.0f);
    EXPECT_EQ(h.part, CYLINDER_BASE_CAP);
    // The cap is a closed disc: at distance exactly 1 from the axis it is hit, one
    // float step further it is not.
    EXPECT_EQ(cyl(ray(vec3(0, 10, -1), vec3(0, -1, 0)), true).t, 6.0f);
    EXPECT_EQ(cyl(ray(vec3(0, 10, std::nextafter(-1.0f, -2.0f)), vec3(0, -1, 0)), true).t, INFINITY_T);
    // Obliquely down (0.6, -0.8, 0) from (-1.5, 5, 0): the top plane is met at t =
    // 1.25, x = -0.75, inside the disc; the side would be later.
    h = cyl(ray(vec3(-1.5f, 5, 0), glm::normalize(vec3(3, -4, 0))), true);
    EXPECT_FLOAT_EQ(h.t, 1.25f);
    EXPECT_EQ(h.part, CYLINDER_TOP_CAP);
    // Open, the same ray enters through the top and meets the far wall at x = 1:
    // t = 2.5 / 0.6, height 5 - 0.8 t = 5 - 10/3 = 5/3.
    h = cyl(ray(vec3(-1.5f, 5, 0), glm::normalize(vec3(3, -4, 0))), false);
    EXPECT_NEAR(h.t, 2.5 / 0.6, 1e-5);
    EXPECT_EQ(h.part, CYLINDER_SIDE);
}

TEST(CylinderIntersect, ARayAlongTheAxis) {
    // Open: it passes through both open ends and meets nothing.
    EXPECT_EQ(cyl(ray(vec3(0, -2, 0), vec3(0, 1, 0)), false).t, INFINITY_T);
    EXPECT_EQ(cyl(ray(vec3(0, 10, 0), vec3(0, -1, 0)), false).t, INFINITY_T);
    // Capped: the near cap, from either end.
    auto h = cyl(ray(vec3(0, -2, 0), vec3(0, 1, 0)), true);
    EXPECT_EQ(h.t, 2.0f);
    EXPECT_EQ(h.part, CYLINDER_BASE_CAP);
    h = cyl(ray(vec3(0, 10, 0), vec3(0, -1, 0)), true);
    EXPECT_EQ(h.t, 6.0f);
    EXPECT_EQ(h.part, CYLINDER_TOP_CAP);
    // Parallel to the axis on the wall itself: the side is never met (A = 0).
    EXPECT_EQ(cyl(ray(vec3(1, -2, 0), vec3(0, 1, 0)), false).t, INFINITY_T);
}

TEST(CylinderIntersect, GrazingTheSideTouchesIt) {
    // Tangent to the side: from (-5, 1, 1) along +x the ray touches the wall at
    // (0, 1, 1). o_perp = (-5, 0, 1), f = (0, 0, 1), disc = 1 - 1 = 0: the double root
    // is kept (as for spheres), C = 25, q = 5, t = 5.
    for (bool capped : {false, true}) {
        const auto h = cyl(ray(vec3(-5, 1, 1), vec3(1, 0, 0)), capped);
        EXPECT_EQ(h.t, 5.0f);
        EXPECT_EQ(h.part, CYLINDER_SIDE);
    }
    // One float step further out the ray misses.
    EXPECT_EQ(cyl(ray(vec3(-5, 1, std::nextafter(1.0f, 2.0f)), vec3(1, 0, 0)), false).t, INFINITY_T);
}

TEST(CylinderIntersect, GrazingTheRimInItsPlane) {
    // In the plane of the top rim (y = 4) along +x: the side's roots are 4 and 6 at
    // height exactly 4 = |top - base|. The segment is closed, so the side is hit at the
    // rim, t = 4, open or capped (the caps are parallel to the ray and not tested).
    for (bool capped : {false, true}) {
        const auto h = cyl(ray(vec3(-5, 4, 0), vec3(1, 0, 0)), capped);
        EXPECT_EQ(h.t, 4.0f);
        EXPECT_EQ(h.part, CYLINDER_SIDE);
    }
    // The same at the base rim (height 0).
    EXPECT_EQ(cyl(ray(vec3(-5, 0, 0), vec3(1, 0, 0)), false).t, 4.0f);
    // One float step above the rim, or a hair below the base, misses.
    EXPECT_EQ(cyl(ray(vec3(-5, std::nextafter(4.0f, 5.0f), 0), vec3(1, 0, 0)), true).t, INFINITY_T);
    EXPECT_EQ(cyl(ray(vec3(-5, -1e-7f, 0), vec3(1, 0, 0)), false).t, INFINITY_T);
}

TEST(CylinderIntersect, MissesBeyondTheSegmentEnds) {
    for (bool capped : {false, true}) {
        EXPECT_EQ(cyl(ray(vec3(-5, 5, 0), vec3(1, 0, 0)), capped).t, INFINITY_T);   // above the top
        EXPECT_EQ(cyl(ray(vec3(-5, -1, 0), vec3(1, 0, 0)), capped).t, INFINITY_T);  // below the base
        EXPECT_EQ(cyl(ray(vec3(-5, 2, 1.5f), vec3(1, 0, 0)), capped).t, INFINITY_T);  // beside it
        EXPECT_EQ(cyl(ray(vec3(-5, 2, 0), vec3(-1, 0, 0)), capped).t, INFINITY_T);  // behind the origin
    }
    // Down past the rim outside the disc: the cap plane is met at distance 1.5.
    EXPECT_EQ(cyl(ray(vec3(1.5f, 10, 0), vec3(0, -1, 0)), true).t, INFINITY_T);
}

TEST(CylinderIntersect, RespectsTheInterval) {
    const auto r = ray(vec3(-5, 1, 0), vec3(1, 0, 0));
    EXPECT_EQ(cyl(r, false, 4.0f).t, INFINITY_T);  // t_max is exclusive
    EXPECT_EQ(cyl(r, false, 5.0f).t, 4.0f);
    EXPECT_EQ(Kernel{}.intersect_cylinder(r, kBase, kTop, 1.0f, false, 4.5f, INFINITY_T).t, 6.0f);  // far wall
}

TEST(CylinderIntersect, AnyAxisAndADegenerateOne) {
    // Radius 2 around the x axis from x = 3 down to x = -1 (top below base), from
    // (1, 0, 10) along -z: the side at z = 2, t = 8.
    Kernel k;
    const auto h = k.intersect_cylinder(ray(vec3(1, 0, 10), vec3(0, 0, -1)), vec3(3, 0, 0), vec3(-1, 0, 0), 2.0f,
                                        true, 0.0f, INFINITY_T);
    EXPECT_EQ(h.t, 8.0f);
    EXPECT_EQ(h.part, CYLINDER_SIDE);
    // Base and top at one point (the loaders refuse it): no hit, and no NaN.
    EXPECT_EQ(k.intersect_cylinder(ray(vec3(0, 0, 10), vec3(0, 0, -1)), vec3(1), vec3(1), 2.0f, true, 0.0f,
                                   INFINITY_T)
                  .t,
              INFINITY_T);
}

TEST(CylinderIntersect, FarAwayOriginsKeepTheirPrecision) {
    // The careful quadratic: from 10^6 away the side of a unit cylinder is still met
    // within a float's rounding of the distance (a b^2 - ac form loses all digits).
    const float far = 1.0e6f;
    const auto h = cyl(ray(vec3(-far, 2, 0.6f), vec3(1, 0, 0)), false);
    EXPECT_NEAR(h.t, double(far) - 0.8, 0.0625);  // one float ULP at 10^6
}

// ---- hit records through the scene: normals, faces, materials ------------------------

// A ring (material 1) and cylinders (2: open, 3: capped) traced by brute force.
struct Scene {
    std::vector<kernel::Material> materials = std::vector<kernel::Material>(4);
    std::vector<kernel::Ring> rings;
    std::vector<kernel::Cylinder> cylinders;

    Kernel kernel() const {
        Kernel k;
        k.HAS_GRID = false;
        k.materials = materials;
        k.rings = rings;
        k.cylinders = cylinders;
        kernel::set_material_count(k.params, std::uint32_t(materials.size()));
        kernel::set_ring_count(k.params, std::uint32_t(rings.size()));
        kernel::set_cylinder_count(k.params, std::uint32_t(cylinders.size()));
        kernel::set_loop_budget(k.params, kernel::DEFAULT_LOOP_BUDGET);
        return k;
    }
};

Scene ring_scene() {
    Scene s;
    s.rings.push_back(kernel::Ring{vec4(0, 0, 0, 1), vec4(0, 0, 1, 2), uvec4(1u, 0u, 0u, 0u)});
    return s;
}

Scene cylinder_scene(bool capped) {
    Scene s;
    s.cylinders.push_back(
        kernel::Cylinder{vec4(0, 0, 0, 1), vec4(0, 4, 0, capped ? 1.0f : 0.0f), uvec4(capped ? 3u : 2u, 0u, 0u, 0u)});
    return s;
}

TEST(RingHit, FrontAndBackFaces) {
    const Scene s = ring_scene();
    Kernel k = s.kernel();
    Kernel::Hit h = k.closest_hit(ray(vec3(1.5f, 0, 5), vec3(0, 0, -1)), INFINITY_T);
    EXPECT_EQ(h.t, 5.0f);
    EXPECT_TRUE(same(h.normal, vec3(0, 0, 1)));
    EXPECT_TRUE(same(h.geo_normal, vec3(0, 0, 1)));
    EXPECT_TRUE(h.front_face);
    EXPECT_EQ(h.material, 1u);
    // From below: the back face, both normals turned toward the ray.
    h = k.closest_hit(ray(vec3(1.5f, 0, -5), vec3(0, 0, 1)), INFINITY_T);
    EXPECT_EQ(h.t, 5.0f);
    EXPECT_TRUE(same(h.normal, vec3(0, 0, -1)));
    EXPECT_TRUE(same(h.geo_normal, vec3(0, 0, -1)));
    EXPECT_FALSE(h.front_face);
    // The hole lets the ray through; a shadow ray through it is not blocked.
    EXPECT_EQ(k.closest_hit(ray(vec3(0.5f, 0, 5), vec3(0, 0, -1)), INFINITY_T).t, INFINITY_T);
    EXPECT_FALSE(k.occluded(ray(vec3(0.5f, 0, 5), vec3(0, 0, -1)), INFINITY_T));
    EXPECT_TRUE(k.occluded(ray(vec3(1.5f, 0, 5), vec3(0, 0, -1)), INFINITY_T));
    EXPECT_FALSE(k.occluded(ray(vec3(1.5f, 0, 5), vec3(0, 0, -1)), 5.0f));
}

TEST(CylinderHitRecord, SideFromOutsideFacesOutward) {
    const Scene s = cylinder_scene(false);
    Kernel k = s.kernel();
    const Kernel::Hit h = k.closest_hit(ray(vec3(-5, 1, 0), vec3(1, 0, 0)), INFINITY_T);
    EXPECT_EQ(h.t, 4.0f);
    EXPECT_TRUE(same(h.normal, vec3(-1, 0, 0)));  // radial at (-1, 1, 0)
    EXPECT_TRUE(same(h.geo_normal, vec3(-1, 0, 0)));
    EXPECT_TRUE(h.front_face);
    EXPECT_EQ(h.material, 2u);
}

TEST(CylinderHitRecord, InsideAnOpenCylinderIsItsBackFace) {
    const Scene s = cylinder_scene(false);
    Kernel k = s.kernel();
    // The far wall at (1, 1, 0): outward normal +x, turned toward the ray.
    const Kernel::Hit h = k.closest_hit(ray(vec3(0, 1, 0), vec3(1, 0, 0)), INFINITY_T);
    EXPECT_EQ(h.t, 1.0f);
    EXPECT_TRUE(same(h.normal, vec3(-1, 0, 0)));
    EXPECT_TRUE(same(h.geo_normal, vec3(-1, 0, 0)));
    EXPECT_FALSE(h.front_face);
    // Looking in through the open top: from (0, 6, 2) along (0, -1, -1) / sqrt(2) the
    // ray crosses z = 1 at y = 5, above the top (no hit there), and meets the far wall
    // z = -1 at y = 3, t = 3 sqrt(2), from inside: outward normal (0, 0, -1), reported
    // turned toward the ray.
    const Kernel::Hit in = k.closest_hit(ray(vec3(0, 6, 2), glm::normalize(vec3(0, -1, -1))), INFINITY_T);
    EXPECT_NEAR(in.t, 3.0 * std::sqrt(2.0), 1e-5);
    EXPECT_FALSE(in.front_face);
    EXPECT_NEAR(in.normal.z, 1.0f, 1e-6f);
    EXPECT_NEAR(in.normal.x, 0.0f, 1e-6f);
}

TEST(CylinderHitRecord, CapsFaceAlongTheAxis) {
    const Scene s = cylinder_scene(true);
    Kernel k = s.kernel();
    // Onto the top cap from above: outward normal +y, front.
    Kernel::Hit h = k.closest_hit(ray(vec3(0.5f, 10, 0.25f), vec3(0, -1, 0)), INFINITY_T);
    EXPECT_EQ(h.t, 6.0f);
    EXPECT_TRUE(same(h.normal, vec3(0, 1, 0)));
    EXPECT_TRUE(h.front_face);
    EXPECT_EQ(h.material, 3u);
    // Onto the base cap from below: outward normal -y, front.
    h = k.closest_hit(ray(vec3(0, -2, 0), vec3(0, 1, 0)), INFINITY_T);
    EXPECT_EQ(h.t, 2.0f);
    EXPECT_TRUE(same(h.normal, vec3(0, -1, 0)));
    EXPECT_TRUE(h.front_face);
    // From inside up to the top cap: its back face, the normal turned down.
    h = k.closest_hit(ray(vec3(0.5f, 1, 0), vec3(0, 1, 0)), INFINITY_T);
    EXPECT_EQ(h.t, 3.0f);
    EXPECT_TRUE(same(h.normal, vec3(0, -1, 0)));
    EXPECT_TRUE(same(h.geo_normal, vec3(0, -1, 0)));
    EXPECT_FALSE(h.front_face);
}

TEST(CylinderHitRecord, GrazingTheSideGivesTheTangentPointsNormal) {
    // The tangent hit at (0, 1, 1): the radial normal (0, 0, 1) is perpendicular to
    // the ray, so dot(n, dir) = 0 is not < 0 and the hit counts as the back face (the
    // rule sphere_hit uses): the normal reported is (0, 0, -1). Either sign is
    // perpendicular to the ray, so shading sees a grazing angle either way.
    const Scene s = cylinder_scene(true);
    Kernel k = s.kernel();
    const Kernel::Hit h = k.closest_hit(ray(vec3(-5, 1, 1), vec3(1, 0, 0)), INFINITY_T);
    EXPECT_EQ(h.t, 5.0f);
    EXPECT_TRUE(same(h.geo_normal, vec3(0, 0, -1)));
    EXPECT_FALSE(h.front_face);
}

TEST(CylinderHitRecord, EveryTestIsCountedAndBudgeted) {
    Scene s = cylinder_scene(true);
    s.rings = ring_scene().rings;
    Kernel k = s.kernel();
    k.work_reset();
    k.closest_hit(ray(vec3(-5, 1, 0), vec3(1, 0, 0)), INFINITY_T);
    EXPECT_EQ(k.g_intersection_tests, 2u);  // one ring, one cylinder
    // The loop budget stops the walk: with room for nothing, nothing is tested.
    kernel::set_loop_budget(k.params, 1u);
    k.work_reset();
    EXPECT_EQ(k.closest_hit(ray(vec3(-5, 1, 0), vec3(1, 0, 0)), INFINITY_T).t, INFINITY_T);
    EXPECT_TRUE(k.budget_exhausted());
}

TEST(CylinderHitRecord, LeftOutKindsAreNotTested) {
    Scene s = cylinder_scene(false);
    Kernel k = s.kernel();
    k.HAS_CYLINDERS = false;
    k.work_reset();
    EXPECT_EQ(k.closest_hit(ray(vec3(-5, 1, 0), vec3(1, 0, 0)), INFINITY_T).t, INFINITY_T);
    EXPECT_EQ(k.g_intersection_tests, 0u);
}

}  // namespace
