// The NFF loader (docs/nff.md), in process: a small file checked field by field,
// every class of malformed line refused with its line number and what was expected,
// cones and cylinders ('c') in both spellings, and every SPD scene in
// scenes/spd loading with the README's primitive counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "scene/cone_mesh.hpp"
#include "scene/json_reader.hpp"
#include "scene/load_scene.hpp"
#include "scene/polygon.hpp"
#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

void expect_vec(const dvec3& actual, const dvec3& expected) {
    EXPECT_DOUBLE_EQ(actual.x, expected.x);
    EXPECT_DOUBLE_EQ(actual.y, expected.y);
    EXPECT_DOUBLE_EQ(actual.z, expected.z);
}

// A fresh directory per test, named for it.
class NffTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::temp_dir(std::string("nff_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& text, const std::string& name = "scene.nff") {
        const fs::path file = dir_ / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

    // Through load_scene, so the .nff dispatch is tested too.
    Scene load(const std::string& text) { return vkrt::load_scene(write(text)); }

    fs::path dir_;
};

// ---- a valid file, field by field ------------------------------------------------

// Tabs, CRLF, comments and blank lines in places, as files from other tools have them.
const std::string kSmallScene =
    "# a small scene with one of everything\r\n"
    "b 0.1 0.2 0.3\r\n"
    "\r\n"
    "v\n"
    "from 1 2 3\n"
    "at\t0 1 0   # where the eye looks\n"
    "up 0 0 2\n"
    "angle 45\n"
    "hither 0.01\n"
    "resolution 64 48\n"
    "l 4 3 2\n"
    "l 1 -4 4 0.5 0.25 1\n"
    "l -3 1 5\n"
    "f 1 0.75 0.33 0.8 0.2 30 0 1\n"  // line 14
    "s 0 1 0 0.5\n"
    "p 5\n"  // a regular pentagon in the plane z = 0, counter-clockwise
    "1 0 0\n"
    "0.309017 0.951057 0\n"
    "-0.809017 0.587785 0\n"
    "-0.809017 -0.587785 0\n"
    "0.309017 -0.951057 0\n"
    "f 1 0.75 0.33 0.8 0.2 30 0 1\n"  // the same again: no new material
    "pp 3\n"
    "0 0 1 0 0 2\n"
    "1 0 1 3 0 4\n"
    "0 1 1 0 0 0.5\n"
    "f 0.5 0.5 0.5 1 0 100000 0.5 1.5\n"  // line 27: glass
    "s\t2 0 0\t+1e-1\n";

TEST_F(NffTest, ReadsEveryFieldOfASmallScene) {
    const Scene s = load(kSmallScene);
    EXPECT_EQ(s.source, dir_ / "scene.nff");

    expect_vec(s.camera.eye, {1, 2, 3});
    expect_vec(s.camera.look_at, {0, 1, 0});
    expect_vec(s.camera.up, {0, 0, 2});
    EXPECT_DOUBLE_EQ(s.camera.fov, 45.0);
    EXPECT_EQ(s.camera.width, 64u);
    EXPECT_EQ(s.camera.height, 48u);

    expect_vec(s.render.background, {0.1, 0.2, 0.3});
    expect_vec(s.render.ambient, {0, 0, 0});
    EXPECT_EQ(s.render.aa, 1u);
    EXPECT_EQ(s.render.samples_per_pixel(), 1u);
    EXPECT_TRUE(s.render.shadows);
    // The SPD rules: pixel corners, depth 5 counting the eye ray, nothing pruned.
    EXPECT_TRUE(s.render.corners);
    EXPECT_EQ(s.render.max_depth, 4u);
    EXPECT_EQ(s.render.min_weight, 0.0);

    // The SPD rule: sqrt(3) / (3 * 2) for each uncoloured light; the coloured one
    // keeps its colour as its brightness.
    ASSERT_EQ(s.lights.size(), 3u);
    const double spd = std::sqrt(3.0) / 6.0;
    expect_vec(s.lights[0].position, {4, 3, 2});
    expect_vec(s.lights[0].color, {1, 1, 1});
    EXPECT_DOUBLE_EQ(s.lights[0].intensity, spd);
    expect_vec(s.lights[1].position, {1, -4, 4});
    expect_vec(s.lights[1].color, {0.5, 0.25, 1});
    EXPECT_DOUBLE_EQ(s.lights[1].intensity, 1.0);
    expect_vec(s.lights[2].position, {-3, 1, 5});
    EXPECT_DOUBLE_EQ(s.lights[2].intensity, spd);

    ASSERT_EQ(s.materials.size(), 2u);
    const auto& plastic = s.materials[0];
    EXPECT_EQ(plastic.name, "nff_line_14");
    expect_vec(plastic.diffuse, {1, 0.75, 0.33});
    EXPECT_DOUBLE_EQ(plastic.kd, 0.8);
    expect_vec(plastic.specular, {1, 1, 1});
    EXPECT_DOUBLE_EQ(plastic.ks, 0.2);
    EXPECT_DOUBLE_EQ(plastic.shininess, 30);
    expect_vec(plastic.reflect, {0.2, 0.2, 0.2});
    expect_vec(plastic.transmit, {0, 0, 0});
    EXPECT_DOUBLE_EQ(plastic.ior, 1.0);
    expect_vec(plastic.emission, {0, 0, 0});
    const auto& glass = s.materials[1];
    EXPECT_EQ(glass.name, "nff_line_27");
    EXPECT_DOUBLE_EQ(glass.ks, 0.0);
    expect_vec(glass.reflect, {0, 0, 0});
    expect_vec(glass.transmit, {0.5, 0.5, 0.5});
    EXPECT_DOUBLE_EQ(glass.ior, 1.5);

    ASSERT_EQ(s.spheres.size(), 2u);
    expect_vec(s.spheres[0].center, {0, 1, 0});
    EXPECT_DOUBLE_EQ(s.spheres[0].radius, 0.5);
    EXPECT_EQ(s.spheres[0].material, 0u);
    expect_vec(s.spheres[1].center, {2, 0, 0});
    EXPECT_DOUBLE_EQ(s.spheres[1].radius, 0.1);
    EXPECT_EQ(s.spheres[1].material, 1u);

    // The pentagon as the fan (0,1,2), (0,2,3), (0,3,4), then the pp triangle.
    ASSERT_EQ(s.triangles.size(), 4u);
    const std::vector<dvec3> pentagon{{1, 0, 0},
                                      {0.309017, 0.951057, 0},
                                      {-0.809017, 0.587785, 0},
                                      {-0.809017, -0.587785, 0},
                                      {0.309017, -0.951057, 0}};
    for (std::size_t k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        const auto& t = s.triangles[k];
        expect_vec(t.vertices[0], pentagon[0]);
        expect_vec(t.vertices[1], pentagon[k + 1]);
        expect_vec(t.vertices[2], pentagon[k + 2]);
        EXPECT_FALSE(t.normals.has_value());
        EXPECT_EQ(t.material, 0u);
    }
    const auto& smooth = s.triangles[3];
    expect_vec(smooth.vertices[0], {0, 0, 1});
    expect_vec(smooth.vertices[1], {1, 0, 1});
    expect_vec(smooth.vertices[2], {0, 1, 1});
    ASSERT_TRUE(smooth.normals.has_value());
    expect_vec((*smooth.normals)[0], {0, 0, 1});  // normalized by the loader
    expect_vec((*smooth.normals)[1], {0.6, 0, 0.8});
    expect_vec((*smooth.normals)[2], {0, 0, 1});
    EXPECT_EQ(smooth.material, 0u);

    // Mirrors and glass render: nothing to warn about.
    EXPECT_TRUE(s.warnings.empty());
    for (const auto& m : s.materials) EXPECT_FALSE(m.fresnel) << "the SPD weights are constant";
}

const std::string kView = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 6\n";

TEST_F(NffTest, ViewLinesMayComeInAnyOrderAndWithoutLightsOrBackground) {
    const Scene s = load("v\nresolution 8 6\nup 0 1 0\nhither 0\nangle 40\nat 0 0 0\nfrom 0 0 5\n");
    expect_vec(s.camera.eye, {0, 0, 5});
    EXPECT_EQ(s.camera.width, 8u);
    EXPECT_TRUE(s.lights.empty());
    EXPECT_TRUE(s.materials.empty());
    expect_vec(s.render.background, {0, 0, 0});
    EXPECT_TRUE(s.warnings.empty());
}

TEST_F(NffTest, UnusedSurfacesMakeNoMaterialAndOnlyUsedOnesWarn) {
    const Scene s = load(kView + "f 1 1 1 1 1 10 0.5 1.5\nf 1 0 0 1 0 10 0 0\ns 0 0 0 1\nf 1 0 0 1 0 10 0 0\n");
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].name, "nff_line_9");
    EXPECT_TRUE(s.warnings.empty());
}

TEST_F(NffTest, LineEndsOfEveryKindCountOnce) {
    // "\r\n", "\r" and "\n" each end one line: the bad sphere is on line 9.
    const std::string view = "v\r\nfrom 0 0 5\rat 0 0 0\nup 0 1 0\r\nangle 40\rhither 1\nresolution 8 6\r";
    const fs::path file = write(view + "f 1 1 1 1 0 10 0 1\r\ns 0 0 0\r\n");
    try {
        vkrt::load_scene(file);
        ADD_FAILURE() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), file.string() + ":9: expected 4 numbers after 's' (x y z radius), got 3");
    }
}

// ---- polygons ----------------------------------------------------------------------

double area(const vkrt::Triangle& t) {
    return glm::length(glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0])) / 2.0;
}

TEST_F(NffTest, NonConvexPolygonIsSplitByEarsThatCoverItExactly) {
    // A comb with two teeth (like the SPD gears' faces): a fan from vertex 0
    // would fill the gaps between the teeth. Its area is 5 * 1 + 2 * 1 = 7.
    const Scene s = load(kView + "f 1 1 1 1 0 10 0 1\np 10\n"
                                 "0 0 0\n5 0 0\n5 2 0\n4 2 0\n4 1 0\n3 1 0\n3 2 0\n2 2 0\n2 1 0\n0 1 0\n");
    ASSERT_EQ(s.triangles.size(), 8u);  // n - 2: no triangle overlaps another
    double total = 0.0;
    for (const auto& t : s.triangles) {
        total += area(t);
        // Every triangle keeps the polygon's winding (front face +z).
        EXPECT_GT(glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]).z, 0.0);
    }
    EXPECT_NEAR(total, 7.0, 1e-12);
    EXPECT_TRUE(s.warnings.empty());
}

TEST_F(NffTest, DegenerateFanTrianglesAreLeftOutWithOneWarning) {
    // A rectangle with an extra vertex on its bottom edge (the 'p' on line 9), and
    // three points on a line (line 15): zero-area triangles are skipped, not refused.
    const Scene s = load(kView + "f 1 1 1 1 0 10 0 1\np 5\n0 0 0\n1 0 0\n2 0 0\n2 1 0\n0 1 0\n"
                                 "p 3\n0 0 1\n1 1 1\n2 2 1\n");
    ASSERT_EQ(s.triangles.size(), 2u);
    EXPECT_NEAR(area(s.triangles[0]) + area(s.triangles[1]), 2.0, 1e-12);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_EQ(s.warnings[0], (dir_ / "scene.nff").string() +
                                 ": left out 2 zero-area triangles of 2 polygons (the first at line 9); they cover "
                                 "nothing");
}

TEST_F(NffTest, SelfCrossingPolygonIsFannedWithAWarning) {
    const Scene s = load(kView + "f 1 1 1 1 0 10 0 1\np 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n");
    EXPECT_EQ(s.triangles.size(), 2u);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("1 polygon crosses itself (the first at line 9)"), std::string::npos)
        << s.warnings[0];
}

TEST(PolygonTest, ConvexityIgnoresCollinearAndRepeatedVertices) {
    const std::vector<dvec3> square{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    EXPECT_TRUE(vkrt::polygon_is_convex(square));
    const std::vector<dvec3> arrow{{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {1, 1, 0}};
    EXPECT_FALSE(vkrt::polygon_is_convex(arrow));
    const auto split = vkrt::triangulate_polygon(arrow);
    ASSERT_EQ(split.triangles.size(), 2u);
    EXPECT_TRUE(split.simple);
    EXPECT_EQ(split.degenerate, 0u);
}

// ---- cones and cylinders ('c') -----------------------------------------------------

TEST_F(NffTest, EqualRadiiMakeAnOpenCylinderInEitherSpelling) {
    // The SPD files' one line of 8 numbers, and the README's 'c' then two lines.
    const Scene s = load(kView + "f 1 1 1 1 0 10 0 1\nc 1 2 3 0.5 1 5 3 0.5\nc\n0 0 0 2\n0 0 -4 2\n");
    ASSERT_EQ(s.cylinders.size(), 2u);
    EXPECT_TRUE(s.triangles.empty());
    expect_vec(s.cylinders[0].base, {1, 2, 3});
    expect_vec(s.cylinders[0].top, {1, 5, 3});
    EXPECT_DOUBLE_EQ(s.cylinders[0].radius, 0.5);
    EXPECT_FALSE(s.cylinders[0].capped);  // NFF cones and cylinders have open ends
    EXPECT_EQ(s.cylinders[0].material, 0u);
    expect_vec(s.cylinders[1].base, {0, 0, 0});
    expect_vec(s.cylinders[1].top, {0, 0, -4});
    EXPECT_DOUBLE_EQ(s.cylinders[1].radius, 2);
}

// Checks a tessellated cone around the y axis from y = 0 (radius r0) to y = h
// (radius r1): every vertex on its circle, front faces outward, and every vertex
// normal unit length, outward and perpendicular to the cone's slope.
void expect_cone_around_y(const std::vector<Triangle>& tris, double r0, double r1, double h) {
    const double slope = (r1 - r0) / h;  // radius gained per unit of height
    for (const Triangle& t : tris) {
        ASSERT_TRUE(t.normals.has_value());
        dvec3 centroid(0.0);
        for (int k = 0; k < 3; ++k) {
            const dvec3& p = t.vertices[k];
            const double r = std::hypot(p.x, p.z);
            const double y = p.y;
            EXPECT_TRUE(std::abs(y) < 1e-12 || std::abs(y - h) < 1e-12) << y;
            EXPECT_NEAR(r, y < h / 2 ? r0 : r1, 1e-12);
            const dvec3& n = (*t.normals)[k];
            EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
            // Perpendicular to the slope (radial * slope + up): n.radial * slope + n.y = 0.
            const double nr = std::hypot(n.x, n.z);
            EXPECT_NEAR(nr * slope + n.y, 0.0, 1e-12);
            centroid += p / 3.0;
        }
        const dvec3 face = glm::cross(t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0]);
        EXPECT_GT(glm::dot(face, dvec3(centroid.x, 0.0, centroid.z)), 0.0) << "front face turned inward";
        const dvec3 n0 = (*t.normals)[0];
        EXPECT_GT(n0.x * centroid.x + n0.z * centroid.z, 0.0) << "normal turned inward";
    }
}

TEST_F(NffTest, DifferentRadiiMakeASmoothConeOfTriangles) {
    // A frustum: radius 2 at the base, 1 at the top, height 3; each side two
    // triangles. Seen from kView's eye 3 units off at 6 rows, it needs 8 sides.
    const Scene s = load(kView + "f 1 1 1 1 0 10 0 1\nc 0 0 0 2 0 3 0 1\n");
    EXPECT_TRUE(s.cylinders.empty());
    EXPECT_EQ(cone_segments({0, 0, 0}, 2, {0, 3, 0}, 1, s.camera), 8u);
    ASSERT_EQ(s.triangles.size(), 2 * 8u);
    expect_cone_around_y(s.triangles, 2.0, 1.0, 3.0);
    for (const Triangle& t : s.triangles) EXPECT_EQ(t.material, 0u);
}

TEST_F(NffTest, AConeWithAnApexHasOneTriangleASide) {
    // Apex radius 0 (the NFF cone), and the reverse: the tip at the base.
    const Scene s = load(kView + "f 1 1 1 1 0 10 0 1\nc 0 0 0 1.5 0 2 0 0\n");
    const std::uint32_t sides = cone_segments({0, 0, 0}, 1.5, {0, 2, 0}, 0, s.camera);
    ASSERT_EQ(s.triangles.size(), sides);
    expect_cone_around_y(s.triangles, 1.5, 0.0, 2.0);
    const Scene tip_down = load(kView + "f 1 1 1 1 0 10 0 1\nc\n0 0 0 0\n0 2 0 1.5\n");
    ASSERT_EQ(tip_down.triangles.size(), sides);
    expect_cone_around_y(tip_down.triangles, 0.0, 1.5, 2.0);
}

TEST(ConeMesh, SidesKeepTheSilhouetteWithinHalfAPixel) {
    // A camera at the origin looking down -z, 90 degrees over 100 rows: a pixel is
    // 0.02 units tall at distance 1.
    vkrt::Camera cam;
    cam.fov = 90.0;
    cam.height = 100;
    const double pixel_at_1 = 2.0 / 100.0;
    auto gap = [](double r, std::uint32_t n) { return r * (1.0 - std::cos(std::acos(-1.0) / n)); };
    // Far and thin: the fewest sides.
    EXPECT_EQ(cone_segments({0, 0, -100}, 0.1, {0, 1, -100}, 0.05, cam), kMinConeSegments);
    // Near and fat: capped at the most.
    EXPECT_EQ(cone_segments({0, 0, -2.05}, 2.0, {0, 1, -2.05}, 0.0, cam), kMaxConeSegments);
    // In between: the fewest that meet the half-pixel bound at the nearest point of
    // the axis (here the base, 10 away) less the radius: 12.
    const std::uint32_t n = cone_segments({0, 0, -10}, 2.0, {0, 0, -20}, 1.0, cam);
    const double pixel = (10.0 - 2.0) * pixel_at_1;
    EXPECT_EQ(n, 12u);
    EXPECT_LE(gap(2.0, n), 0.5 * pixel);
    EXPECT_GT(gap(2.0, n - 1), 0.5 * pixel);
    // The nearest point of a long cone seen from its side is in its middle, not at an end.
    EXPECT_EQ(cone_segments({-50, 0, -10}, 2.0, {50, 0, -10}, 1.5, cam), n);
}

TEST(ConeMesh, AnyAxisGivesTheSameConeTurned) {
    // Along -x from (1, 1, 1): every vertex at its radius from the axis, on the end planes.
    const std::vector<Triangle> tris = tessellate_cone({1, 1, 1}, 0.5, {-3, 1, 1}, 0.25, 7u, 5);
    ASSERT_EQ(tris.size(), 10u);
    for (const Triangle& t : tris) {
        EXPECT_EQ(t.material, 7u);
        for (const dvec3& p : t.vertices) {
            const double r = std::hypot(p.y - 1.0, p.z - 1.0);
            EXPECT_TRUE(std::abs(p.x - 1.0) < 1e-12 || std::abs(p.x + 3.0) < 1e-12);
            EXPECT_NEAR(r, p.x > -1.0 ? 0.5 : 0.25, 1e-12);
        }
    }
}

// ---- malformed files ---------------------------------------------------------------

struct BadNff {
    std::string name;
    std::string text;     // the whole file
    int line;             // 0: the message names no line
    std::string message;  // after "<file>:<line>: "
};

void PrintTo(const BadNff& c, std::ostream* os) { *os << c.name; }

// kView, a material on line 8, then the case's lines from line 9.
std::string after_view(const std::string& lines) { return kView + "f 1 1 1 1 0 10 0 1\n" + lines; }

std::string view_with(const std::string& key, const std::string& value) {
    std::string text = kView;
    const std::size_t at = text.find("\n" + key + " ") + 1;
    text.replace(at, text.find('\n', at) - at, key + " " + value);
    return text + "f 1 1 1 1 0 10 0 1\ns 0 0 0 1\n";
}

std::vector<BadNff> bad_cases() {
    const std::string huge = fmt::format("{}", vkrt::json::kMaxMagnitude);
    return {
        {"sphere_three_numbers", after_view("s 0 0 0\n"), 9, "expected 4 numbers after 's' (x y z radius), got 3"},
        {"sphere_word", after_view("s 0 0 zero 1\n"), 9, "'s' z: expected a number, got 'zero'"},
        {"sphere_trailing_text", after_view("s 0 0 0 1x\n"), 9, "'s' radius: expected a number, got '1x'"},
        {"sphere_negative_radius", after_view("s 0 0 0 -1\n"), 9, "'s' radius: expected a number > 0, got -1"},
        {"sphere_zero_radius", after_view("s 0 0 0 0\n"), 9, "'s' radius: expected a number > 0, got 0"},
        {"sphere_infinite", after_view("s 0 0 inf 1\n"), 9, "'s' z: expected a finite number, got 'inf'"},
        {"sphere_overflow", after_view("s 0 1e999 0 1\n"), 9, "'s' y: expected a finite number, got '1e999'"},
        {"sphere_huge", after_view("s 1e13 0 0 1\n"), 9,
         "'s' x: expected a number of magnitude at most " + huge + ", got 1e13"},
        {"sphere_before_any_f", kView + "s 0 0 0 1\n", 8,
         "'s' comes before any 'f' line, so it has no material (an 'f' line sets the material of the objects after "
         "it)"},
        {"polygon_two_vertices", after_view("p 2\n0 0 0\n1 0 0\n"), 9,
         "'p' vertex count: expected a whole number in [3, 1048576], got 2"},
        {"polygon_fractional_count", after_view("p 3.5\n"), 9, "'p' vertex count: expected a whole number, got 3.5"},
        {"polygon_truncated", after_view("p 4\n0 0 0\n1 0 0\n"), 9,
         "the file ends after 2 of the 4 vertex lines of this 'p'"},
        {"polygon_short_vertex", after_view("p 3\n0 0 0\n1 0\n0 1 0\n"), 11,
         "expected 3 numbers on vertex line 2 of the 'p' at line 9 (x y z), got 2"},
        {"polygon_count_too_large", after_view("p 4\n0 0 0\n1 0 0\n0 1 0\ns 0 0 0 1\n"), 13,
         "expected vertex 4 of 4 of the 'p' at line 9, got a 's' line (is the vertex count right?)"},
        {"polygon_count_too_small", after_view("p 3\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n"), 13,
         "a line of numbers where an entity (v, b, l, f, s, p, pp, c) should start; does the polygon above have "
         "more vertex lines than its count says?"},
        {"pp_vertex_without_normal", after_view("pp 3\n0 0 0 0 0 1\n1 0 0\n0 1 0 0 0 1\n"), 11,
         "expected 6 numbers on vertex line 2 of the 'pp' at line 9 (x y z nx ny nz), got 3"},
        {"pp_zero_normal", after_view("pp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n"), 11,
         "'pp' vertex 2 normal: expected a non-zero vector, got [0, 0, 0]"},
        {"cone_seven_numbers", after_view("c 0 0 0 1 0 1 0\n"), 9,
         "expected 8 numbers after 'c' (base x y z r0 apex x y z r1), or none and then two lines x y z r, got 7"},
        {"cone_word", after_view("c 0 0 0 1 0 one 0 1\n"), 9, "'c' apex y: expected a number, got 'one'"},
        {"cone_negative_radius", after_view("c 0 0 0 -1 0 1 0 1\n"), 9,
         "'c' base radius: expected a number >= 0, got -1"},
        {"cone_radii_zero", after_view("c 0 0 0 0 0 1 0 0\n"), 9,
         "'c': the base and apex radii are both 0, so it has no surface"},
        {"cone_no_axis", after_view("c 1 2 3 1 1 2 3 0.5\n"), 9,
         "'c': the base [1, 2, 3] and apex [1, 2, 3] are the same point (in single precision), so it has no axis"},
        {"cone_two_line_short", after_view("c\n0 0 0 1\n0 1 0\n"), 11,
         "expected 4 numbers on line 2 of 2 of the 'c' at line 9 (x y z radius), got 3"},
        {"cone_two_line_truncated", after_view("c\n0 0 0 1\n"), 9,
         "the file ends after 1 of the 2 lines (x y z radius) of this 'c'"},
        {"cone_two_line_interrupted", after_view("c\n0 0 0 1\ns 0 0 0 1\n"), 11,
         "expected line 2 of 2 (x y z radius) of the 'c' at line 9, got a 's' line"},
        {"cone_two_line_negative", after_view("c\n0 0 0 1\n0 1 0 -2\n"), 11,
         "'c' apex radius: expected a number >= 0, got -2"},
        {"cone_before_surface", kView + "c 0 0 0 1 0 1 0 1\n", 8,
         "'c' comes before any 'f' line, so it has no material (an 'f' line sets the material of the objects after "
         "it)"},
        {"unknown_entity", after_view("t 1 2 3\n"), 9, "unknown entity 't' (expected one of: v, b, l, f, s, p, pp, c)"},
        {"light_four_numbers", after_view("l 1 2 3 4\n"), 9, "expected 3 or 6 numbers after 'l' (x y z [r g b]), got 4"},
        {"light_negative_colour", after_view("l 1 2 3 1 -1 1\n"), 9, "'l' g: expected a number >= 0, got -1"},
        {"background_two_numbers", after_view("b 0.1 0.2\n"), 9, "expected 3 numbers after 'b' (r g b), got 2"},
        {"surface_seven_numbers", after_view("f 1 1 1 1 0 10 0\n"), 9,
         "expected 8 numbers after 'f' (r g b Kd Ks Shine T ior), got 7"},
        {"surface_negative_kd", after_view("f 1 1 1 -0.5 0 10 0 1\n"), 9, "'f' Kd: expected a number >= 0, got -0.5"},
        {"glass_without_ior", after_view("f 1 1 1 0 0 10 0.9 0\n"), 9,
         "'f' ior: expected a number > 0 for a transmitting surface (T = 0.9), got 0"},
        {"view_truncated", "v\nfrom 0 0 5\nat 0 0 0\n", 1,
         "the file ends inside this view block, which lacks up, angle, hither and resolution"},
        {"view_interrupted", "v\nfrom 0 0 5\ns 0 0 0 1\n", 3,
         "expected at, up, angle, hither or resolution in the view block that starts at line 1, got 's'"},
        {"view_key_twice", "v\nfrom 0 0 5\nfrom 0 0 4\n", 3, "'from' given twice in the view block (first at line 2)"},
        {"view_key_outside_view", after_view("angle 30\n"), 9,
         "'angle' outside a view block (it belongs among the lines after a 'v')"},
        {"second_view", after_view(kView), 9, "a second view block ('v'); the first is at line 1"},
        {"no_view", "f 1 1 1 1 0 10 0 1\ns 0 0 0 1\n", 0,
         "no view block (a 'v' line, then from, at, up, angle, hither and resolution lines)"},
        {"angle_180", view_with("angle", "180"), 5, "'angle': expected a number strictly between 0 and 180, got 180"},
        {"angle_zero", view_with("angle", "0"), 5, "'angle': expected a number strictly between 0 and 180, got 0"},
        {"at_equals_from", view_with("at", "0 0 5"), 3, "'at' must differ from 'from' (both are [0, 0, 5])"},
        {"up_zero", view_with("up", "0 0 0"), 4, "'up': expected a non-zero vector, got [0, 0, 0]"},
        {"up_along_view", view_with("up", "0 0 1"), 4,
         "'up' [0, 0, 1] is parallel to the view direction at - from = [0, 0, -5]"},
        {"resolution_zero", view_with("resolution", "0 6"), 7,
         "'resolution' width: expected a whole number in [1, 32768], got 0"},
        {"resolution_too_large", view_with("resolution", "30000 30000"), 7,
         "image of 30000x30000 pixels traces 30001x30001 corner rays (render.corners), more than the limit of "
         "33554432"},
        // The largest image a JSON scene may have is one row and column too many for
        // the corner rays NFF scenes trace.
        {"resolution_too_large_for_corners", view_with("resolution", "8192 4096"), 7,
         "image of 8192x4096 pixels traces 8193x4097 corner rays (render.corners), more than the limit of 33554432"},
        {"hither_word", view_with("hither", "near"), 6, "'hither': expected a number, got 'near'"},
    };
}

using BadNffTest = ::testing::TestWithParam<BadNff>;

TEST_P(BadNffTest, FailsWithItsLineAndWhatWasExpected) {
    const BadNff& c = GetParam();
    const fs::path dir = test::temp_dir("nff_bad_" + c.name);
    const fs::path file = dir / (c.name + ".nff");
    std::ofstream(file, std::ios::binary) << c.text;
    const std::string where = c.line > 0 ? fmt::format("{}:{}", file.string(), c.line) : file.string();
    try {
        vkrt::load_scene(file);
        ADD_FAILURE() << "no SceneError for:\n" << c.text;
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), where + ": " + c.message);
    }
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Lines, BadNffTest, ::testing::ValuesIn(bad_cases()),
                         [](const ::testing::TestParamInfo<BadNff>& p) { return p.param.name; });

// ---- through the program -----------------------------------------------------------

TEST_F(NffTest, ProgramPrintsWarningsAndRendersUpRightAndRight) {
    // Looking along +y with z up (the SPD's habit): a sphere above the view axis
    // must land in the top half, one at +x in the right half.
    const fs::path file = write(
        "v\nfrom 0 -5 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 16 16\n"
        "l 0 -5 0\nf 1 1 1 1 0.5 10 0 1\ns 0 0 1 0.4\ns 1 0 0 0.4\np 3\n0 0 0\n1 0 0\n2 0 0\n");
    const Scene scene = vkrt::load_scene(file);
    const vkrt::RenderOutcome out = test::render_cpu(scene);
    const auto lit = [&out](std::uint32_t x, std::uint32_t y) { return out.image.pixel(x, y)[0] > 0.1f; };
    EXPECT_TRUE(lit(8, 3));    // above the centre
    EXPECT_FALSE(lit(8, 12));  // below it: nothing there
    EXPECT_TRUE(lit(12, 8));   // right of the centre
    EXPECT_FALSE(lit(3, 8));   // left of it: nothing there

    const test::ProgramRun run = test::run_vkrt(
        fmt::format("render {} -o {} --backend cpu -q", test::shell_quote(file.string()),
                    test::shell_quote((dir_ / "out.png").string())),
        dir_);
    EXPECT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_EQ(run.stderr_text, "warning: " + file.string() +
                                   ": left out 1 zero-area triangle of 1 polygon (the first at line 12); they cover "
                                   "nothing\n");
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

TEST_F(NffTest, ProgramFailsWithOneErrorLine) {
    const fs::path file = write(after_view("s 0 0 0\n"), "bad.nff");
    const test::ProgramRun run = test::run_vkrt(
        fmt::format("render {} -o {} --backend cpu", test::shell_quote(file.string()),
                    test::shell_quote((dir_ / "out.png").string())),
        dir_);
    EXPECT_EQ(run.code, 1);
    EXPECT_EQ(run.stderr_text,
              "error: " + file.string() + ":9: expected 4 numbers after 's' (x y z radius), got 3\n");
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

// ---- the Standard Procedural Databases -------------------------------------------

struct SpdExpectation {
    std::size_t spheres = 0;
    std::size_t triangles = 0;
    std::size_t smooth_triangles = 0;  // of triangles, from 'pp' and cones
    std::size_t cylinders = 0;
    std::size_t lights = 0;
    std::uint32_t resolution = 512;
    double fov = 45.0;
};

// Counts from scenes/spd/README.md: one triangle per 'p 3' or 'pp 3', two per
// quadrilateral, n - 2 per n-gon (gears: 9,217 quadrilaterals and 128 faces of 144
// vertices, 9,345 polygons); a cylinder per 'c' of equal radii; 2 smooth triangles
// per side of a cone frustum (tree's 4,095 cones all have two non-zero radii; 4,068
// of them get 6 sides, the 27 nearest the eye 7 to 15: 49,292 triangles).
const std::map<std::string, SpdExpectation>& spd_expectations() {
    static const std::map<std::string, SpdExpectation> e{
        {"balls", {.spheres = 7381, .triangles = 2, .lights = 3}},
        {"gears", {.triangles = 9217 * 2 + 128 * 142, .lights = 5}},
        {"jacks", {.spheres = 6, .cylinders = 3, .lights = 1, .resolution = 256, .fov = 25.0}},
        {"lattice", {.spheres = 2197, .cylinders = 6084, .lights = 6, .fov = 60.0}},
        {"mount", {.spheres = 4, .triangles = 8192, .lights = 1}},
        {"rings", {.spheres = 4200, .triangles = 2, .cylinders = 4200, .lights = 3}},
        {"shells", {.spheres = 5761, .lights = 1}},
        {"teapot", {.triangles = 2256 + 36 * 2, .smooth_triangles = 2256, .lights = 2}},
        {"tetra", {.triangles = 4096, .lights = 1}},
        {"tree",
         {.spheres = 4095,
          .triangles = 2 + 49292,
          .smooth_triangles = 49292,
          .lights = 7}},
    };
    return e;
}

TEST(SpdTest, EveryFileLoadsWithThePublishedCounts) {
    const fs::path dir = test::source_dir() / "scenes" / "spd";
    ASSERT_TRUE(fs::is_directory(dir)) << "missing SPD scenes: " << dir;
    std::vector<std::string> seen;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (vkrt::format_extension(entry.path()) != ".nff") continue;
        const std::string name = vkrt::scene_stem(entry.path());
        SCOPED_TRACE(name);
        seen.push_back(name);
        const auto it = spd_expectations().find(name);
        ASSERT_NE(it, spd_expectations().end()) << "an SPD file this test does not know: " << entry.path();
        const SpdExpectation& want = it->second;
        const Scene s = vkrt::load_scene(entry.path());
        EXPECT_EQ(s.spheres.size(), want.spheres);
        EXPECT_EQ(s.triangles.size(), want.triangles);
        EXPECT_EQ(std::count_if(s.triangles.begin(), s.triangles.end(),
                                [](const vkrt::Triangle& t) { return t.normals.has_value(); }),
                  static_cast<std::ptrdiff_t>(want.smooth_triangles));
        EXPECT_EQ(s.cylinders.size(), want.cylinders);
        EXPECT_TRUE(s.rings.empty());
        EXPECT_EQ(s.lights.size(), want.lights);
        EXPECT_EQ(s.camera.width, want.resolution);
        EXPECT_EQ(s.camera.height, want.resolution);
        EXPECT_DOUBLE_EQ(s.camera.fov, want.fov);
        const double spd = std::sqrt(double(want.lights)) / (2.0 * double(want.lights));
        for (const auto& light : s.lights) EXPECT_DOUBLE_EQ(light.intensity, spd);
    }
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(seen.size(), spd_expectations().size()) << "SPD files missing from " << dir;
}

TEST(SpdTest, BallsMaterials) {
    const fs::path file = test::source_dir() / "scenes" / "spd" / "balls.nff.gz";
    const Scene s = vkrt::load_scene(file);
    // The floor (f on line 12) and the balls (line 18), nothing else.
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].name, "nff_line_12");
    expect_vec(s.materials[0].diffuse, {1, 0.75, 0.33});
    EXPECT_DOUBLE_EQ(s.materials[0].ks, 0.0);
    EXPECT_EQ(s.materials[1].name, "nff_line_18");
    expect_vec(s.materials[1].reflect, {0.5, 0.5, 0.5});
    EXPECT_DOUBLE_EQ(s.materials[1].shininess, 3.0827);
    expect_vec(s.render.background, {0.078, 0.361, 0.753});
    expect_vec(s.camera.up, {0, 0, 1});
    EXPECT_TRUE(s.warnings.empty());
}

TEST(SpdTest, GearFacesAreSplitWithoutFillingTheGapsBetweenTeeth) {
    // Each 144-vertex face is non-convex; its triangles must add up to its area,
    // which a fan from vertex 0 would exceed.
    const fs::path file = test::source_dir() / "scenes" / "spd" / "gears.nff.gz";
    std::istringstream in(vkrt::read_text(file, file.string(), "scene"));
    double faces_area = 0.0;  // by the shoelace formula on the file's first face (z = const)
    std::string line;
    while (std::getline(in, line) && line != "p 144") {
    }
    std::vector<dvec3> face;
    for (int k = 0; k < 144 && std::getline(in, line); ++k) {
        double x = 0, y = 0, z = 0;
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf", &x, &y, &z), 3);
        face.push_back({x, y, z});
    }
    ASSERT_EQ(face.size(), 144u);
    for (std::size_t k = 0; k < face.size(); ++k) {
        const dvec3& a = face[k];
        const dvec3& b = face[(k + 1) % face.size()];
        faces_area += (a.x * b.y - b.x * a.y) / 2.0;
    }
    EXPECT_FALSE(vkrt::polygon_is_convex(face));
    const auto split = vkrt::triangulate_polygon(face);
    ASSERT_EQ(split.triangles.size(), 142u);
    EXPECT_TRUE(split.simple);
    double sum = 0.0;
    for (const auto& [a, b, c] : split.triangles) {
        sum += glm::length(glm::cross(face[b] - face[a], face[c] - face[a])) / 2.0;
    }
    EXPECT_NEAR(sum, std::abs(faces_area), 1e-9 * std::abs(faces_area));
}

}  // namespace
