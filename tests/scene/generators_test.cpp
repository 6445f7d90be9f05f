// Scene objects that expand at load time: "random_spheres" (the same spheres on
// every machine, within the stated bounds), "sphereflake" (Haines' recursive
// spheres: the stated count, each child touching its parent on the outward side,
// nothing overlapping) and "torus_knot" (a closed, outward tube of the stated size
// and triangle count), and their bad fields refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <numbers>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "scene/generators.hpp"
#include "scene/json_scene_loader.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

class GeneratorsTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::temp_dir(std::string("generators_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    void TearDown() override { fs::remove_all(dir_); }

    // A scene with materials "a", "b", "c" and the one object `object`.
    fs::path write(const std::string& object) {
        const fs::path file = dir_ / "scene.json";
        std::ofstream(file) << fmt::format(R"({{"camera": {{"eye": [0, 0, 5], "look_at": [0, 0, 0]}},
            "materials": {{"a": {{}}, "b": {{}}, "c": {{}}}}, "objects": [{}]}})", object);
        return file;
    }

    Scene load(const std::string& object) { return vkrt::load_json_scene(write(object)); }

    void expect_error(const std::string& object, std::initializer_list<std::string_view> pieces) {
        const fs::path file = write(object);
        try {
            vkrt::load_json_scene(file);
            ADD_FAILURE() << "no SceneError for: " << object;
        } catch (const SceneError& e) {
            test::expect_error_message(e.what(), file.string() + ": objects[0]", pieces);
        }
    }

    fs::path dir_;
};

// ---- the random number generator ---------------------------------------------

TEST(SplitMix64, MatchesTheReferenceOutput) {
    // The first outputs of Vigna's splitmix64.c seeded with 1234567.
    vkrt::SplitMix64 rng(1234567);
    EXPECT_EQ(rng.next(), 6457827717110365317ull);
    EXPECT_EQ(rng.next(), 3203168211198807973ull);
    EXPECT_EQ(rng.next(), 9817491932198370423ull);
}

TEST(SplitMix64, UniformIsTheTop53BitsAndBelowOne) {
    vkrt::SplitMix64 a(1), b(1);
    EXPECT_EQ(a.uniform(), static_cast<double>(b.next() >> 11) / 9007199254740992.0);
    for (int i = 0; i < 100000; ++i) {
        const double u = a.uniform();
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
    }
}

// ---- random_spheres -------------------------------------------------------------

const std::string kSpheres = R"({"type": "random_spheres", "count": 1000, "seed": 1, "min": [-1, -2, -3],
    "max": [1, 2, 3], "radius": [0.5, 2], "materials": ["a", "b", "c"]})";

TEST_F(GeneratorsTest, RandomSpheresAreTheSameForTheSameSeed) {
    const Scene s = load(kSpheres);
    ASSERT_EQ(s.spheres.size(), 1000u);
    // Pinned: a change to the generator or to the order of draws changes every
    // generated scene, and must be noticed (values from an independent splitmix64
    // in Python, with the same arithmetic).
    EXPECT_EQ(s.spheres[0].center, dvec3(0.1331231503445618, 0.9831270290508045, 2.8260165215207778));
    EXPECT_EQ(s.spheres[0].radius, 1.1665388255836582);
    EXPECT_EQ(s.spheres[0].material, 1u);

    const Scene again = load(kSpheres);
    ASSERT_EQ(again.spheres.size(), s.spheres.size());
    for (std::size_t i = 0; i < s.spheres.size(); ++i) {
        EXPECT_EQ(again.spheres[i].center, s.spheres[i].center);
        EXPECT_EQ(again.spheres[i].radius, s.spheres[i].radius);
        EXPECT_EQ(again.spheres[i].material, s.spheres[i].material);
    }
    std::string other = kSpheres;
    other.replace(other.find("\"seed\": 1"), 9, "\"seed\": 2");
    EXPECT_NE(load(other).spheres[0].center, s.spheres[0].center);
}

TEST_F(GeneratorsTest, RandomSpheresStayInTheirBounds) {
    const Scene s = load(kSpheres);
    std::map<std::uint32_t, int> used;
    dvec3 lo(1e300), hi(-1e300);
    for (const vkrt::Sphere& sp : s.spheres) {
        lo = glm::min(lo, sp.center);
        hi = glm::max(hi, sp.center);
        EXPECT_GE(sp.radius, 0.5);
        EXPECT_LE(sp.radius, 2.0);
        ++used[sp.material];
    }
    EXPECT_GE(lo.x, -1.0);
    EXPECT_GE(lo.y, -2.0);
    EXPECT_GE(lo.z, -3.0);
    EXPECT_LE(hi.x, 1.0);
    EXPECT_LE(hi.y, 2.0);
    EXPECT_LE(hi.z, 3.0);
    // 1000 uniform draws fill the box: each side within 1% of its end.
    EXPECT_LT(lo.x, -0.98);
    EXPECT_GT(hi.z, 2.94);
    // Each of the three materials about a third of the time (binomial sd ~15).
    ASSERT_EQ(used.size(), 3u);
    for (const auto& [material, n] : used) {
        EXPECT_NEAR(n, 333, 60) << material;
    }
}

TEST_F(GeneratorsTest, RandomSpheresDefaultsAndDegenerateRanges) {
    // seed defaults to 1; a flat box and a single radius are allowed.
    const Scene s = load(R"({"type": "random_spheres", "count": 3, "min": [0, 1, 0], "max": [2, 1, 0],
                             "radius": [0.25, 0.25], "materials": ["c"]})");
    ASSERT_EQ(s.spheres.size(), 3u);
    vkrt::SplitMix64 rng(1);
    const double x = 2 * rng.uniform();
    EXPECT_EQ(s.spheres[0].center, dvec3(x, 1, 0));
    for (const vkrt::Sphere& sp : s.spheres) {
        EXPECT_EQ(sp.radius, 0.25);
        EXPECT_EQ(sp.material, 2u);
    }
}

TEST_F(GeneratorsTest, RandomSpheresBadFields) {
    const auto with = [](std::string_view field, std::string_view value) {
        std::string text = R"({"type": "random_spheres", "count": 10, "seed": 1, "min": [0, 0, 0], "max": [1, 1, 1],
                               "radius": [0.1, 0.2], "materials": ["a"]})";
        const auto at = text.find(fmt::format("\"{}\": ", field));
        const auto start = at + field.size() + 4;
        const auto end = text[start] == '[' ? text.find(']', start) + 1 : text.find_first_of(",}", start);
        return text.replace(start, end - start, value);
    };
    expect_error(with("count", "0"), {"objects[0].count: expected a whole number in [1, 10000000], got 0"});
    expect_error(with("count", "10000001"), {"objects[0].count: ", "got 10000001"});
    expect_error(with("count", "2.5"), {"objects[0].count: expected a whole number"});
    expect_error(with("seed", "-1"), {"objects[0].seed: ", "got -1"});
    expect_error(with("max", "[1, -1, 1]"), {"objects[0].max: expected max >= min in every component", "[1]"});
    expect_error(with("min", "[0, 0]"), {"objects[0].min: expected an array of 3 numbers"});
    expect_error(with("radius", "[0, 1]"), {"objects[0].radius[0]: expected a number > 0, got 0"});
    expect_error(with("radius", "[0.5, 0.25]"), {"objects[0].radius[1]: expected a number >= radius[0] (0.5), got 0.25"});
    expect_error(with("radius", "0.5"), {"objects[0].radius: expected an array [smallest, largest] of 2 numbers"});
    expect_error(with("materials", "[]"), {"objects[0].materials: expected at least one material name"});
    expect_error(with("materials", R"(["a", "zz"])"), {"objects[0].materials[1]: unknown material 'zz'"});
    expect_error(with("materials", R"("a")"), {"objects[0].materials: expected an array"});
    expect_error(R"({"type": "random_spheres", "count": 1, "min": [0, 0, 0], "max": [1, 1, 1], "radius": [1, 1],
                    "materials": ["a"], "material": "a"})",
                 {"objects[0]: unknown field 'material'", "materials"});
    expect_error(R"({"type": "random_spheres", "min": [0, 0, 0], "max": [1, 1, 1], "radius": [1, 1], "materials": ["a"]})",
                 {"objects[0].count: required field is missing"});
}

// ---- sphereflake -----------------------------------------------------------------

// The flake's spheres are listed level by level, so the parent of sphere i > 0 is
// sphere (i - 1) / 9 (docs/scene-format.md).
std::size_t parent_of(std::size_t i) { return (i - 1) / 9; }

TEST_F(GeneratorsTest, SphereflakeHasNinePowersOfSpheresLevelByLevel) {
    for (int levels = 0; levels <= 4; ++levels) {
        const Scene s = load(fmt::format(R"({{"type": "sphereflake", "center": [1, 2, 3], "radius": 2,
                                              "levels": {}, "material": "b"}})", levels));
        std::uint64_t nine_power = 1;  // 9^(levels + 1)
        for (int i = 0; i <= levels; ++i) nine_power *= 9;
        ASSERT_EQ(s.spheres.size(), (nine_power - 1) / 8) << levels;
        EXPECT_EQ(vkrt::sphereflake_count(levels), s.spheres.size());
        EXPECT_EQ(s.spheres[0].center, dvec3(1, 2, 3));
        EXPECT_EQ(s.spheres[0].radius, 2.0);
        // Level L holds 9^L spheres of radius 2 / 3^L.
        std::size_t index = 0, count = 1;
        double radius = 2.0;
        for (int level = 0; level <= levels; ++level, count *= 9, radius /= 3.0) {
            for (std::size_t k = 0; k < count; ++k, ++index) {
                ASSERT_NEAR(s.spheres[index].radius, radius, 1e-15) << "level " << level;
                EXPECT_EQ(s.spheres[index].material, 1u);
            }
        }
    }
    EXPECT_EQ(vkrt::sphereflake_count(4), 7381u);  // the SPD "balls" default, 1 + 9 + 81 + 729 + 6561
    EXPECT_EQ(vkrt::sphereflake_count(6), 597871u);
}

// The direction a sphere's children grow towards: away from its parent, or the
// flake's axis for the root.
dvec3 outward(const std::vector<vkrt::Sphere>& s, std::size_t i, const dvec3& axis) {
    return i == 0 ? axis : glm::normalize(s[i].center - s[parent_of(i)].center);
}

TEST_F(GeneratorsTest, SphereflakeChildrenTouchTheirParentOnTheOutwardSide) {
    const dvec3 axis = glm::normalize(dvec3(1, 2, -0.5));
    const Scene s = load(R"({"type": "sphereflake", "center": [0.5, -1, 2], "radius": 1.5, "axis": [2, 4, -1],
                             "material": "a"})");
    ASSERT_EQ(s.spheres.size(), 7381u);  // levels default to 4
    const double sin_up = std::sqrt(2.0 / 3.0);
    for (std::size_t p = 0; p < 820; ++p) {
        const dvec3 up = outward(s.spheres, p, axis);
        int ring = 0, top = 0;
        for (std::size_t i = 9 * p + 1; i <= 9 * p + 9; ++i) {
            const vkrt::Sphere& child = s.spheres[i];
            const vkrt::Sphere& parent = s.spheres[p];
            EXPECT_NEAR(child.radius, parent.radius / 3.0, 1e-15);  // ratio defaults to 1/3
            const dvec3 d = child.center - parent.center;
            // Touching: the centres are the two radii apart.
            ASSERT_NEAR(glm::length(d), parent.radius + child.radius, 1e-12) << i;
            // Outward: 6 in the parent's equator (perpendicular to the way it grows),
            // 3 at sin^2(elevation) = 2/3 above it; none below.
            const double elevation = glm::dot(glm::normalize(d), up);
            ASSERT_GT(elevation, -1e-12) << i;
            if (std::abs(elevation) < 1e-12) ++ring;
            if (std::abs(elevation - sin_up) < 1e-12) ++top;
        }
        EXPECT_EQ(ring, 6) << p;
        EXPECT_EQ(top, 3) << p;
    }
}

TEST_F(GeneratorsTest, SphereflakeChildrenAreSixtyDegreesFromTheirNearestSiblings) {
    const Scene s = load(R"({"type": "sphereflake", "center": [0, 0, 0], "radius": 1, "levels": 2, "material": "a"})");
    for (std::size_t p = 0; p < 10; ++p) {
        for (std::size_t i = 9 * p + 1; i <= 9 * p + 9; ++i) {
            int nearest = 0;
            for (std::size_t j = 9 * p + 1; j <= 9 * p + 9; ++j) {
                if (j == i) continue;
                const double cosine = glm::dot(glm::normalize(s.spheres[i].center - s.spheres[p].center),
                                               glm::normalize(s.spheres[j].center - s.spheres[p].center));
                EXPECT_LT(cosine, 0.5 + 1e-12) << i << " " << j;  // never closer than 60 degrees
                nearest += std::abs(cosine - 0.5) < 1e-12;
            }
            // A ring child has 2 ring neighbours and the top child 30 degrees of azimuth
            // away; a top child the 2 other top children and the 2 ring children 30
            // degrees of azimuth either side of it.
            EXPECT_EQ(nearest, i - 9 * p <= 6 ? 3 : 4) << i;
        }
    }
}

TEST_F(GeneratorsTest, SphereflakeSpheresDoNotOverlap) {
    // Every pair of the default flake (7381 spheres, 27 million pairs) is apart,
    // except a child and its parent, which touch. The closest other pair leaves a
    // gap of 2/81 of the root's radius (found by this test, printed below).
    const Scene s = load(R"({"type": "sphereflake", "center": [0, 0, 0], "radius": 1, "material": "a"})");
    const std::vector<vkrt::Sphere>& sp = s.spheres;
    double smallest_gap = 1e300;
    for (std::size_t i = 1; i < sp.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            if (j == parent_of(i)) continue;
            const double gap = glm::length(sp[i].center - sp[j].center) - sp[i].radius - sp[j].radius;
            smallest_gap = std::min(smallest_gap, gap);
        }
    }
    EXPECT_GT(smallest_gap, 0.0);
    std::printf("smallest gap between spheres that are not parent and child: %.6g\n", smallest_gap);
}

TEST_F(GeneratorsTest, SphereflakePlacementIsPinned) {
    // With the default axis y, the root's frame is u = x, v = -z: the first ring child
    // lies along +x and the last top child (azimuth 270 degrees, along -v) faces +z.
    const Scene s = load(R"({"type": "sphereflake", "center": [0, 1, 0], "radius": 3, "levels": 1,
                             "ratio": 0.5, "material": "c"})");
    ASSERT_EQ(s.spheres.size(), 10u);
    const auto near = [](const dvec3& a, const dvec3& b) { return glm::length(a - b) < 1e-12; };
    EXPECT_TRUE(near(s.spheres[1].center, dvec3(4.5, 1, 0)));
    EXPECT_TRUE(near(s.spheres[2].center, dvec3(4.5 * 0.5, 1, -4.5 * std::sqrt(0.75))));
    EXPECT_TRUE(near(s.spheres[9].center, dvec3(0, 1 + 4.5 * std::sqrt(2.0 / 3.0), 4.5 * std::sqrt(1.0 / 3.0))));
    EXPECT_EQ(s.spheres[9].radius, 1.5);
}

TEST_F(GeneratorsTest, SphereflakeAfterOtherSpheresCountsFromItsFirst) {
    const Scene s = load(R"({"type": "sphere", "center": [9, 9, 9], "radius": 1, "material": "a"},
                            {"type": "sphereflake", "center": [0, 0, 0], "radius": 1, "levels": 1, "material": "b"})");
    ASSERT_EQ(s.spheres.size(), 11u);
    EXPECT_EQ(s.spheres[0].center, dvec3(9, 9, 9));
    EXPECT_EQ(s.spheres[1].center, dvec3(0, 0, 0));
    for (std::size_t i = 2; i < 11; ++i) EXPECT_NEAR(glm::length(s.spheres[i].center), 4.0 / 3.0, 1e-12);
}

TEST_F(GeneratorsTest, GalleryImageIIsTheSpdSphereflake) {
    const Scene s = vkrt::load_json_scene(test::source_dir() / "scenes" / "gallery" / "i_sphereflake.json");
    EXPECT_EQ(s.spheres.size(), 7381u);
    EXPECT_TRUE(s.warnings.empty());
}

TEST_F(GeneratorsTest, SphereflakeBadFields) {
    const std::string ok = R"("type": "sphereflake", "center": [0, 0, 0], "radius": 1, "material": "a")";
    const auto with = [&](std::string_view extra) { return fmt::format("{{{}, {}}}", ok, extra); };
    expect_error(with(R"("levels": 7)"), {"objects[0].levels: expected a whole number in [0, 6], got 7"});
    expect_error(with(R"("levels": -1)"), {"objects[0].levels: expected a whole number in [0, 6], got -1"});
    expect_error(with(R"("levels": 2.5)"), {"objects[0].levels: expected a whole number"});
    expect_error(with(R"("ratio": 0)"), {"objects[0].ratio: expected a number > 0, got 0"});
    expect_error(with(R"("ratio": 1.5)"), {"objects[0].ratio: expected a number in (0, 1], got 1.5"});
    expect_error(with(R"("axis": [0, 0, 0])"), {"objects[0].axis: expected a non-zero vector, got [0, 0, 0]"});
    expect_error(with(R"("axis": [0, 1])"), {"objects[0].axis: expected an array of 3 numbers"});
    expect_error(with(R"("materials": ["a"])"), {"objects[0]: unknown field 'materials'", "ratio"});
    expect_error(with(R"("levels": 6, "ratio": 1e-8)"),
                 {"objects[0]: the smallest spheres' radius", "too small for the renderer's single precision"});
    expect_error(R"({"type": "sphereflake", "center": [0, 0, 0], "radius": 0, "material": "a"})",
                 {"objects[0].radius: expected a number > 0, got 0"});
    expect_error(R"({"type": "sphereflake", "radius": 1, "material": "a"})",
                 {"objects[0].center: required field is missing"});
    expect_error(R"({"type": "sphereflake", "center": [0, 0, 0], "material": "a"})",
                 {"objects[0].radius: required field is missing"});
    expect_error(R"({"type": "sphereflake", "center": [0, 0, 0], "radius": 1})",
                 {"objects[0].material: required field is missing"});
    expect_error(R"({"type": "sphereflake", "center": [0, 0, 0], "radius": 1, "material": "zz"})",
                 {"objects[0].material: unknown material 'zz'"});
}

// ---- torus_knot -----------------------------------------------------------------

// The knot's length, by summing many short chords of its centre line.
double knot_length(int p, int q, double radius) {
    double length = 0.0;
    constexpr int kSteps = 200000;
    for (int i = 0; i < kSteps; ++i) {
        const double t0 = 2 * std::numbers::pi * i / kSteps, t1 = 2 * std::numbers::pi * (i + 1) / kSteps;
        length += glm::length(vkrt::torus_knot_point(p, q, radius, t1) - vkrt::torus_knot_point(p, q, radius, t0));
    }
    return length;
}

// A closed surface with consistent winding has every directed edge once and its
// reverse once; its signed volume (divergence theorem) is then positive exactly
// when the front faces point out.
double closed_signed_volume(const std::vector<Triangle>& triangles) {
    std::map<std::tuple<double, double, double, double, double, double>, int> edges;
    double volume = 0.0;
    for (const Triangle& t : triangles) {
        for (int k = 0; k < 3; ++k) {
            const dvec3& a = t.vertices[k];
            const dvec3& b = t.vertices[(k + 1) % 3];
            ++edges[{a.x, a.y, a.z, b.x, b.y, b.z}];
        }
        volume += glm::dot(t.vertices[0], glm::cross(t.vertices[1], t.vertices[2])) / 6.0;
    }
    for (const auto& [edge, count] : edges) {
        const auto [ax, ay, az, bx, by, bz] = edge;
        EXPECT_EQ(count, 1);
        const auto reverse = edges.find({bx, by, bz, ax, ay, az});
        EXPECT_TRUE(reverse != edges.end() && reverse->second == 1) << "open or inconsistently wound edge";
    }
    return volume;
}

TEST_F(GeneratorsTest, TorusKnotHasTheStatedSizeAndCount) {
    const Scene s = load(R"({"type": "torus_knot", "p": 3, "q": 5, "radius": 2, "tube": 0.1, "segments": [300, 12],
                             "material": "b", "smooth": true})");
    ASSERT_EQ(s.triangles.size(), 2u * 300 * 12);
    EXPECT_TRUE(s.warnings.empty());
    double nearest = 1e300, farthest = 0.0;
    for (const Triangle& t : s.triangles) {
        EXPECT_EQ(t.material, 1u);
        for (const dvec3& v : t.vertices) {
            const double from_axis = std::hypot(v.x, v.y);
            nearest = std::min(nearest, from_axis);
            farthest = std::max(farthest, from_axis);
            EXPECT_LE(std::abs(v.z), 2.0 / 3.0 + 0.1 + 1e-12);
        }
    }
    // Within radius + tube of the z axis, and no nearer than the torus's inner
    // side (radius / 3) less the tube; both bounds nearly reached.
    EXPECT_LE(farthest, 2.0 + 0.1 + 1e-12);
    EXPECT_GT(farthest, 2.0 + 0.1 - 0.01);
    EXPECT_GE(nearest, 2.0 / 3.0 - 0.1 - 1e-12);
    EXPECT_LT(nearest, 2.0 / 3.0 - 0.1 + 0.01);
}

TEST_F(GeneratorsTest, TorusKnotIsAClosedOutwardTube) {
    const Scene s = load(R"({"type": "torus_knot", "p": 2, "q": 3, "radius": 1, "tube": 0.1, "segments": [600, 24],
                             "material": "a", "smooth": true})");
    for (const Triangle& t : s.triangles) {
        ASSERT_TRUE(t.normals.has_value());
        const dvec3 g = glm::normalize(glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]));
        for (const dvec3& n : *t.normals) {
            EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
            EXPECT_GT(glm::dot(n, g), 0.9);  // the exact normal of a fine tessellation
        }
    }
    // The tube's volume is pi tube^2 times the knot's length (Pappus), less the
    // polygon's shortfall from a circle: 24 sides keep 98.9% of the area.
    const double volume = closed_signed_volume(s.triangles);
    const double expected = std::numbers::pi * 0.01 * knot_length(2, 3, 1.0);
    EXPECT_NEAR(volume / expected, 24 * std::sin(2 * std::numbers::pi / 24) / (2 * std::numbers::pi), 2e-3);
}

TEST_F(GeneratorsTest, TorusKnotMirroredStaysOutward) {
    const Scene s = load(R"({"type": "torus_knot", "segments": [120, 8], "tube": 0.1, "material": "a",
                             "transform": {"scale": [-1, 1, 1], "translate": [0, 0, 0]}})");
    EXPECT_GT(closed_signed_volume(s.triangles), 0.0);
    EXPECT_FALSE(s.triangles[0].normals.has_value());  // smooth defaults to false
}

TEST_F(GeneratorsTest, TorusKnotDefaults) {
    const Scene s = load(R"({"type": "torus_knot", "material": "a"})");
    EXPECT_EQ(s.triangles.size(), 2u * 256 * 16);  // segments [256, 16]
    double farthest = 0.0;
    for (const Triangle& t : s.triangles) {
        for (const dvec3& v : t.vertices) farthest = std::max(farthest, std::hypot(v.x, v.y));
    }
    EXPECT_LE(farthest, 1.25 + 1e-12);  // radius 1, tube 0.25
    EXPECT_GT(farthest, 1.24);
}

TEST_F(GeneratorsTest, GalleryImageJHasAtLeast80000SmoothTriangles) {
    const Scene s = vkrt::load_json_scene(test::source_dir() / "scenes" / "gallery" / "j_torus_knot.json");
    std::size_t smooth = 0;
    for (const Triangle& t : s.triangles) smooth += t.normals.has_value();
    EXPECT_EQ(smooth, 90000u);
    EXPECT_TRUE(s.warnings.empty());
    const Scene h = vkrt::load_json_scene(test::source_dir() / "scenes" / "gallery" / "h_random_spheres.json");
    EXPECT_EQ(h.spheres.size(), 100000u);
}

TEST_F(GeneratorsTest, TorusKnotBadFields) {
    expect_error(R"({"type": "torus_knot", "p": 0, "material": "a"})", {"objects[0].p: expected a whole number in [1, 1000], got 0"});
    expect_error(R"({"type": "torus_knot", "q": 1.5, "material": "a"})", {"objects[0].q: expected a whole number"});
    expect_error(R"({"type": "torus_knot", "radius": 0, "material": "a"})", {"objects[0].radius: expected a number > 0"});
    expect_error(R"({"type": "torus_knot", "tube": -1, "material": "a"})", {"objects[0].tube: expected a number > 0"});
    expect_error(R"({"type": "torus_knot", "segments": [2, 10], "material": "a"})",
                 {"objects[0].segments[0]: expected a whole number in [3, "});
    expect_error(R"({"type": "torus_knot", "segments": [100], "material": "a"})",
                 {"objects[0].segments: expected an array [along, around] of 2 whole numbers"});
    expect_error(R"({"type": "torus_knot", "segments": [10000, 10000], "material": "a"})",
                 {"objects[0].segments: 10000 x 10000 segments make 200000000 triangles, more than the limit of 20000000"});
    expect_error(R"({"type": "torus_knot"})", {"objects[0].material: required field is missing"});
    expect_error(R"({"type": "torus_knot", "material": "a", "smooth": 1})", {"objects[0].smooth: expected true or false"});
    expect_error(R"({"type": "torus_knot", "material": "a", "turns": 3})", {"objects[0]: unknown field 'turns'", "segments"});
    expect_error(R"({"type": "torus_knot", "material": "a", "radius": 1e12})",
                 {"objects[0]: the mesh has a vertex at", "beyond the largest coordinate allowed"});
    expect_error(R"({"type": "torus_knot", "material": "a", "transform": {"scale": 0}})",
                 {"objects[0].transform.scale: expected a non-zero scale factor"});
}

}  // namespace
