// Brute force's deferred sphere tests (deferred_spheres.glsl): a sphere the ray
// starts near (sphere_needs_exact_c) is set aside by the loop and tested error-free
// after it, four per pass of the loop, and a ray that met more makes another pass.
// Whatever the path, the result must be intersect_sphere's on every sphere: the
// nearest hit, its reference, the blocker of a shadow ray (which defers nothing);
// and every pass counts its tests. DEFERRED_SPHERES is on (the Kernel's default)
// except where a test turns it off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::INFINITY_T;
using vkrt::kernel::Kernel;
using vkrt::kernel::Sphere;
using vkrt::kernel::uvec4;
using vkrt::kernel::vec3;
using vkrt::kernel::vec4;
namespace kernel = vkrt::kernel;

vec3 unit(vec3 v) { return v / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

// The ray every test traces: from a point just outside each "touching" sphere below,
// so each of them needs the error-free test.
const vec3 kOrigin(0.25f, 0.5f, -0.125f);
const vec3 kDir = unit(vec3(0.3f, -0.2f, -1.0f));

// Spheres of radius kRadius centred 1 from kOrigin in these directions, so that the
// origin lies 0.001 outside each (not on it: rounding would put it inside some, and
// they would be hit at t ~ 0). Those whose centre lies ahead of the ray (positive
// dot with kDir) are hit at about t = 0.001 / cos(angle): nearest along the ray.
constexpr float kRadius = 0.999f;
std::vector<vec3> touching_directions() {
    return {unit(vec3(1, 0, 0)),   unit(vec3(0.3f, -0.2f, -1)), unit(vec3(0, 1, 0)),  unit(vec3(-1, 0, 0.2f)),
            unit(vec3(1, 1, -1)),  unit(vec3(0, 0, 1)),         unit(vec3(2, -1, -1)), unit(vec3(0, -1, 0))};
}

// The spheres in the given order: touching ones with a far sphere off the
// ray between each pair, so that the deferred ones are not neighbours in the array.
std::vector<Sphere> scene_spheres(const std::vector<vec3>& directions) {
    std::vector<Sphere> spheres;
    for (std::size_t i = 0; i < directions.size(); ++i) {
        spheres.push_back(Sphere{vec4(kOrigin + directions[i], kRadius), uvec4(0u)});
        spheres.push_back(Sphere{vec4(vec3(40.0f + float(i), 30.0f, -5.0f), 0.5f), uvec4(0u)});
    }
    return spheres;
}

Kernel brute_force(const std::vector<Sphere>& spheres) {
    Kernel k;
    k.HAS_GRID = false;
    k.HAS_TRIANGLES = false;
    k.HAS_AREA_LIGHTS = false;
    k.spheres = spheres;
    kernel::set_sphere_count(k.params, static_cast<std::uint32_t>(spheres.size()));
    kernel::set_loop_budget(k.params, kernel::DEFAULT_LOOP_BUDGET);
    return k;
}

// intersect_sphere on each sphere in turn: the nearest t in (0, t_max) and its index.
struct Expected {
    float t = INFINITY_T;
    std::uint32_t index = 0;
};
Expected one_by_one(Kernel& k, const std::vector<Sphere>& spheres, float t_max) {
    Expected e{t_max, 0};
    for (std::uint32_t i = 0; i < spheres.size(); ++i) {
        const float t = k.intersect_sphere(Kernel::Ray(kOrigin, kDir), vec3(spheres[i].center_radius),
                                           spheres[i].center_radius.w, 0.0f, e.t);
        if (t < e.t) e = Expected{t, i};
    }
    return e;
}

constexpr std::uint32_t sphere_ref(std::uint32_t index) {
    return (kernel::REF_SPHERE << kernel::REF_KIND_SHIFT) | index;
}

TEST(DeferredSpheres, EveryTouchingSphereNeedsTheErrorFreeTest) {
    Kernel k = brute_force({});
    for (const vec3& d : touching_directions()) {
        EXPECT_TRUE(k.sphere_needs_exact_c(k.sphere_setup(Kernel::Ray(kOrigin, kDir), kOrigin + d, kRadius)));
    }
    EXPECT_FALSE(k.sphere_needs_exact_c(k.sphere_setup(Kernel::Ray(kOrigin, kDir), vec3(40, 30, -5), 0.5f)));
}

// With the nearest touching sphere (the one straight ahead) moved to each of the
// eight places, so that it is found in each slot of the first pass or the second.
TEST(DeferredSpheres, TheNearestHitIsFoundWhereverItWasDeferred) {
    const std::vector<vec3> base = touching_directions();
    const std::size_t nearest = 1;
    for (std::size_t place = 0; place < base.size(); ++place) {
        std::vector<vec3> directions = base;
        std::swap(directions[nearest], directions[place]);
        const std::vector<Sphere> spheres = scene_spheres(directions);
        Kernel k = brute_force(spheres);
        const Expected want = one_by_one(k, spheres, INFINITY_T);
        ASSERT_EQ(want.index, 2 * place) << "the sphere straight ahead is the nearest";
        k.g_intersection_tests = 0;
        const Kernel::Nearest got = k.trace(Kernel::Ray(kOrigin, kDir), INFINITY_T, false);
        EXPECT_EQ(got.t, want.t) << "place " << place;
        EXPECT_EQ(got.ref, sphere_ref(want.index)) << "place " << place;
        EXPECT_EQ(k.g_intersection_tests, 2 * spheres.size()) << "eight near spheres: two passes";
        EXPECT_FALSE(k.budget_exhausted());
    }
}

// The hit of each touching sphere alone, one after the other as the nearest: with
// t_max just above it, every nearer sphere has been moved out of the way.
TEST(DeferredSpheres, EachDeferredSphereCanBeTheNearest) {
    const std::vector<Sphere> spheres = scene_spheres(touching_directions());
    std::size_t hits = 0;
    for (std::uint32_t i = 0; i < spheres.size(); i += 2) {
        std::vector<Sphere> alone = spheres;
        for (std::uint32_t j = 0; j < alone.size(); j += 2) {
            if (j != i) alone[j].center_radius = vec4(vec3(-40.0f, -30.0f, 5.0f + float(j)), 0.5f);
        }
        Kernel one = brute_force(alone);
        const Expected want = one_by_one(one, alone, INFINITY_T);
        one.g_intersection_tests = 0;
        const Kernel::Nearest got = one.trace(Kernel::Ray(kOrigin, kDir), INFINITY_T, false);
        EXPECT_EQ(got.t, want.t) << "sphere " << i;
        EXPECT_EQ(one.g_intersection_tests, alone.size()) << "one near sphere: one pass";
        if (want.t < INFINITY_T) {
            EXPECT_EQ(got.ref, sphere_ref(i)) << "sphere " << i;
            ++hits;
        } else {
            EXPECT_EQ(got.ref, kernel::REF_NONE) << "sphere " << i;
        }
    }
    EXPECT_GE(hits, 3u) << "the test needs touching spheres ahead of the ray";
}

// A sphere tested by the rounded form, hit between the deferred spheres' hits (about
// t = 0.002: radius 0.004, its centre 0.006 ahead, 1.5 radii from the origin), and
// the touching spheres in varying numbers: 5 (two passes, the second with one), 8,
// and 9 (three passes). Whichever is nearer wins, wherever it lies in the array.
TEST(DeferredSpheres, RoundedAndDeferredHitsBoundEachOther) {
    const Sphere rounded{vec4(kOrigin + 0.006f * kDir, 0.004f), uvec4(0u)};
    std::vector<vec3> nine = touching_directions();
    nine.push_back(unit(vec3(0.5f, -0.5f, -1.0f)));
    bool rounded_won = false, deferred_won = false;
    for (const std::size_t touching : {5u, 8u, 9u}) {
        for (const bool ahead_turned_away : {false, true}) {
            std::vector<vec3> directions(nine.begin(), nine.begin() + std::ptrdiff_t(touching));
            if (ahead_turned_away) {  // leave only hits beyond the rounded sphere's
                for (vec3& d : directions) {
                    if (d.x * kDir.x + d.y * kDir.y + d.z * kDir.z > 0.5f) d = -d;
                }
            }
            for (const bool rounded_first : {true, false}) {
                std::vector<Sphere> spheres = scene_spheres(directions);
                spheres.insert(rounded_first ? spheres.begin() : spheres.end(), rounded);
                Kernel k = brute_force(spheres);
                ASSERT_FALSE(k.sphere_needs_exact_c(k.sphere_setup(Kernel::Ray(kOrigin, kDir),
                                                                   vec3(rounded.center_radius), 0.004f)));
                const Expected want = one_by_one(k, spheres, INFINITY_T);
                k.g_intersection_tests = 0;
                const Kernel::Nearest got = k.trace(Kernel::Ray(kOrigin, kDir), INFINITY_T, false);
                EXPECT_EQ(got.t, want.t) << touching << " touching, turned " << ahead_turned_away;
                EXPECT_EQ(got.ref, sphere_ref(want.index)) << touching << " touching";
                EXPECT_EQ(k.g_intersection_tests, spheres.size() * ((touching + 3) / 4)) << "a pass per four";
                const bool rounded_is_nearest = spheres[want.index].center_radius == rounded.center_radius;
                rounded_won = rounded_won || rounded_is_nearest;
                deferred_won = deferred_won || !rounded_is_nearest;
            }
        }
    }
    EXPECT_TRUE(rounded_won);
    EXPECT_TRUE(deferred_won);
}

// With DEFERRED_SPHERES off (few spheres: host/flatten/flat_scene.cpp) the loop tests
// each sphere in place, once: the same nearest hit and the same blocker.
TEST(DeferredSpheres, OffTheLoopTestsInPlaceWithTheSameResult) {
    const std::vector<Sphere> spheres = scene_spheres(touching_directions());
    Kernel deferred = brute_force(spheres);
    Kernel in_place = brute_force(spheres);
    in_place.DEFERRED_SPHERES = false;
    const Kernel::Nearest want = deferred.trace(Kernel::Ray(kOrigin, kDir), INFINITY_T, false);
    const Kernel::Nearest got = in_place.trace(Kernel::Ray(kOrigin, kDir), INFINITY_T, false);
    EXPECT_EQ(got.t, want.t);
    EXPECT_EQ(got.ref, want.ref);
    EXPECT_EQ(got.t, one_by_one(in_place, spheres, INFINITY_T).t);
    EXPECT_EQ(in_place.g_intersection_tests, spheres.size()) << "one pass";
    EXPECT_EQ(in_place.occluded(Kernel::Ray(kOrigin, kDir), got.t * 1.01f), true);
    EXPECT_EQ(in_place.occluded(Kernel::Ray(kOrigin, kDir), got.t * 0.99f), false);
}

// A shadow ray defers nothing (its test, sphere_blocks, needs no error-free c): over
// the eight touching spheres it tests each in place, once, and is blocked by the last
// of them, the only one ahead; with t_max before that blocker it is not.
TEST(DeferredSpheres, AShadowRayTestsEveryTouchingSphereInPlace) {
    std::vector<vec3> directions = touching_directions();
    // Only the last touching sphere lies ahead of the ray: turn the others away.
    for (std::size_t i = 0; i + 1 < directions.size(); ++i) {
        if (directions[i].x * kDir.x + directions[i].y * kDir.y + directions[i].z * kDir.z > 0.0f) {
            directions[i] = -directions[i];
        }
    }
    directions.back() = unit(vec3(0.3f, -0.2f, -1.0f) + vec3(0.5f, 0.5f, 0.0f));
    const std::vector<Sphere> spheres = scene_spheres(directions);
    Kernel k = brute_force(spheres);
    const Expected want = one_by_one(k, spheres, INFINITY_T);
    ASSERT_LT(want.t, INFINITY_T);
    ASSERT_EQ(want.index, spheres.size() - 2) << "the last touching sphere is the only one hit";
    k.g_intersection_tests = 0;
    EXPECT_EQ(k.trace(Kernel::Ray(kOrigin, kDir), INFINITY_T, true).ref, sphere_ref(want.index));
    EXPECT_EQ(k.g_intersection_tests, want.index + 1) << "one pass, ending at the blocker";
    EXPECT_TRUE(k.occluded(Kernel::Ray(kOrigin, kDir), want.t * 1.01f));
    k.g_intersection_tests = 0;
    EXPECT_FALSE(k.occluded(Kernel::Ray(kOrigin, kDir), want.t * 0.99f));
    EXPECT_EQ(k.g_intersection_tests, spheres.size()) << "one pass over every sphere";
}

}  // namespace
