// Leave out what the scene does not need: the feature set and the buffers built.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

Scene spheres_only() {
    Scene s;
    s.camera.eye = {0, 0, 4};
    s.camera.width = 16;
    s.camera.height = 12;
    s.camera.look_at = {0, 0, 0};
    Material m;
    m.diffuse = {0.5, 0.5, 0.5};
    s.materials.push_back(m);
    s.lights.push_back(Light{{1, 2, 3}, {1, 1, 1}, 1});
    s.spheres.push_back(Sphere{{0, 0, 0}, 1, 0});
    return s;
}

TEST(Features, SpheresOnlySceneLeavesTrianglesOut) {
    const FlatScene g = flatten_scene(spheres_only());
    EXPECT_TRUE(g.features.has(Feature::HAS_SPHERES));
    EXPECT_FALSE(g.features.has(Feature::HAS_TRIANGLES));
    EXPECT_FALSE(g.features.has(Feature::HAS_SMOOTH_NORMALS));
    EXPECT_FALSE(g.features.has(Feature::HAS_SPECULAR));  // ks is 0
    EXPECT_TRUE(g.features.has(Feature::HAS_SHADOWS));
    EXPECT_TRUE(g.triangles.empty());
    for (const BufferSize& b : g.built_buffers()) EXPECT_NE(b.name, "triangles");
    EXPECT_TRUE(contains(g.features.left_out(), "triangles"));
    EXPECT_TRUE(contains(g.features.kept(), "spheres"));
}

TEST(Features, ShadowsOffLeavesShadowCodeOut) {
    Scene s = spheres_only();
    s.render.shadows = false;
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::HAS_SHADOWS));
    s.lights.clear();
    s.render.shadows = true;
    const FlatScene g = flatten_scene(s);
    EXPECT_FALSE(g.features.has(Feature::HAS_SHADOWS));
    EXPECT_FALSE(g.features.has(Feature::HAS_POINT_LIGHTS));
    EXPECT_TRUE(g.lights.empty());
}

// Point lights alone leave the spot and directional code out; one of either kind
// brings it in.
TEST(Features, DirectedLightsOnlyWithASpotOrDirectionalLight) {
    Scene s = spheres_only();
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::HAS_DIRECTED_LIGHTS));
    EXPECT_TRUE(contains(flatten_scene(s).features.left_out(), "directed_lights"));
    for (const LightType type : {LightType::Spot, LightType::Directional}) {
        Scene t = s;
        t.lights.push_back(Light{{0, 3, 0}, {1, 1, 1}, 1, type});
        const FlatScene g = flatten_scene(t);
        EXPECT_TRUE(g.features.has(Feature::HAS_DIRECTED_LIGHTS));
        EXPECT_TRUE(g.features.has(Feature::HAS_POINT_LIGHTS)) << "the loop over the lights";
        EXPECT_EQ(g.lights.size(), 2u);
    }
}

// The records the kernel reads (kernel/layout.glsl, Light): a point light at w = 1
// with the cone that passes everything, a directional light as the point at infinity
// toward it, a spot light's cone as the ramp (cos - cos(outer)) / (cos(inner) - cos(outer)).
TEST(Features, LightRecordsFoldEachKindIntoOneLayout) {
    Scene s = spheres_only();
    s.camera.eye = {100, 0, 4};  // the kernel's origin moves to (128, 0, 0)
    s.lights = {Light{{1, 2, 3}, {1, 0.5, 0.25}, 2},
                Light{{0, 0, 0}, {1, 1, 1}, 3, LightType::Directional, {0.6, -0.8, 0}},
                Light{{0, 5, 0}, {1, 1, 1}, 1, LightType::Spot, {0, -1, 0}, glm::radians(10.0), glm::radians(30.0)}};
    const FlatScene g = flatten_scene(s);
    ASSERT_EQ(g.lights.size(), 3u);
    EXPECT_EQ(g.lights[0].position, glm::vec4(-127, 2, 3, 1));
    EXPECT_EQ(g.lights[0].radiance, glm::vec4(2, 1, 0.5, 0));
    EXPECT_EQ(g.lights[0].cone, glm::vec4(0, 0, 0, 1));
    EXPECT_EQ(g.lights[1].position, glm::vec4(-0.6f, 0.8f, 0, 0));
    EXPECT_EQ(g.lights[1].radiance, glm::vec4(3, 3, 3, 0));
    EXPECT_EQ(g.lights[1].cone, glm::vec4(0, 0, 0, 1));
    EXPECT_EQ(g.lights[2].position, glm::vec4(-128, 5, 0, 1));
    const double ci = std::cos(glm::radians(10.0)), co = std::cos(glm::radians(30.0));
    const glm::vec4 cone = g.lights[2].cone;
    EXPECT_FLOAT_EQ(cone.y, float(-1.0 / (ci - co)));
    EXPECT_FLOAT_EQ(cone.w, float(-co / (ci - co)));
    // Along the inner and outer edges the ramp is 1 and 0.
    EXPECT_NEAR(cone.y * -ci + cone.w, 1.0, 1e-5);
    EXPECT_NEAR(cone.y * -co + cone.w, 0.0, 1e-5);
}

TEST(Features, TrianglesWithNormalsKeepSmoothNormals) {
    Scene s = spheres_only();
    Triangle t;
    t.vertices = {dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0)};
    s.triangles.push_back(t);
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::HAS_SMOOTH_NORMALS));
    s.triangles[0].normals = std::array<dvec3, 3>{dvec3(0, 0, 1), dvec3(0, 0, 1), dvec3(0, 0, 1)};
    const FlatScene g = flatten_scene(s);
    EXPECT_TRUE(g.features.has(Feature::HAS_SMOOTH_NORMALS));
    EXPECT_EQ(g.triangles.size(), 1u);
}

// The terminator lift moves shadow rays: it needs smooth normals and shadows, and
// the scene may turn it off.
TEST(Features, TerminatorNeedsSmoothNormalsAndShadows) {
    Scene s = spheres_only();
    Triangle t;
    t.vertices = {dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0)};
    s.triangles.push_back(t);
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::HAS_TERMINATOR));
    s.triangles[0].normals = std::array<dvec3, 3>{dvec3(0, 0, 1), dvec3(0, 0, 1), dvec3(0, 0, 1)};
    EXPECT_TRUE(flatten_scene(s).features.has(Feature::HAS_TERMINATOR));
    s.render.shadows = false;
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::HAS_TERMINATOR));
    s.render.shadows = true;
    s.render.terminator = false;
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::HAS_TERMINATOR));
}

// Brute force defers the spheres a ray starts near past its loop from 8 spheres on;
// with the grid, or fewer spheres, the loop tests them in place.
TEST(Features, DeferredSpheresOnlyForBruteForceOverManySpheres) {
    Scene s = spheres_only();
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::DEFERRED_SPHERES));  // one sphere
    for (int i = 1; i < 7; ++i) s.spheres.push_back(Sphere{{3.0 * i, 0, 0}, 1, 0});
    s.render.grid.mode = GridMode::Off;
    EXPECT_FALSE(flatten_scene(s).features.has(Feature::DEFERRED_SPHERES));  // seven
    s.spheres.push_back(Sphere{{21.0, 0, 0}, 1, 0});
    EXPECT_TRUE(flatten_scene(s).features.has(Feature::DEFERRED_SPHERES));  // eight
    s.render.grid.mode = GridMode::On;
    const FlatScene grid = flatten_scene(s);
    ASSERT_TRUE(grid.grid.used);
    EXPECT_FALSE(grid.features.has(Feature::DEFERRED_SPHERES));
}

// The program's --stats report says what was kept and left out, for both backends.
TEST(Features, StatsReportNamesWhatWasLeftOut) {
    const auto dir = test::temp_dir("features_test");
    const auto scene = dir / "spheres.json";
    std::ofstream(scene) << R"({
        "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "width": 32, "height": 24},
        "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
        "lights": [{"type": "point", "position": [1, 2, 3]}],
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
    for (const std::string backend : {"cpu", "vulkan"}) {
        const auto stats = dir / ("stats_" + backend + ".json");
        const test::ProgramRun run =
            test::run_vkrt("render " + test::shell_quote(scene.string()) + " -q --validate --backend " + backend +
                               " -o " + test::shell_quote((dir / "out.png").string()) + " --stats " +
                               test::shell_quote(stats.string()),
                           dir);
        ASSERT_EQ(run.code, 0) << run.stderr_text;
        const auto report = nlohmann::json::parse(std::ifstream(stats));
        EXPECT_EQ(report["backend"], backend);
        EXPECT_EQ(report["width"], 32);
        EXPECT_EQ(report["rays"]["eye"], 32 * 24);
        EXPECT_TRUE(contains(report["features"]["left_out"], "triangles"));
        EXPECT_TRUE(contains(report["features"]["kept"], "spheres"));
        EXPECT_FALSE(report["buffers"].contains("triangles"));
        EXPECT_TRUE(report["buffers"].contains("spheres"));
        EXPECT_EQ(report["validation_messages"], 0);
        EXPECT_GT(report["seconds"]["total"].get<double>(), 0.0);
    }
}

}  // namespace
