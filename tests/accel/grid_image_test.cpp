// The grid must not change the image: every shipped scene, rendered with the grid and
// by brute force, gives the same image (max abs difference <= 1e-5) on each backend.
// Brute force on the Vulkan backend needs every primitive test of a sample within the
// per-invocation loop budget (lavapipe stops longer loops), so scenes where one sample
// would run past it (many primitives, or mirrors multiplying the rays of a sample)
// compare the Vulkan grid image with the reference's brute-force image instead,
// under the cross-check's tolerance (crosscheck/crosscheck_test.cpp). The reference runs brute
// force with the budget lifted.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "image/compare.hpp"
#include "kernel/types.hpp"
#include "render/fingerprint.hpp"
#include "scene/load_scene.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;

// Scenes with more primitives than this, or whose samples would not fit the loop
// budget by brute force (below), render brute force on the cpu backend only, and at
// a quarter of the pixels, to keep the test in seconds.
constexpr std::size_t kBruteForceOnVulkanMax = 20000;

// Whether one sample, traced by brute force, stays within the kernel's loop budget:
// each ray loops over every primitive (plus a loop entry per kind, and two for the
// deferred spheres, deferred_spheres.glsl). In local mode a sample traces its eye
// ray and, with mirrors or glass, up to max_depth more along the ray tree, each
// sending a shadow ray per point light and per area-light sample; in global mode a
// path traces its eye ray and up to max_bounces more, each sending a shadow ray per
// light and, with next-event estimation, one toward the emitters or the sky. One
// pass over the spheres per ray: a ray that starts near more than four makes more
// (deferred_spheres.glsl). An estimate that errs low shows up as truncated samples,
// which the test fails on.
bool brute_force_fits_loop_budget(const Scene& s, std::size_t primitives) {
    bool secondary = false, emits = false;
    for (const Material& m : s.materials) {
        secondary = secondary || m.reflect != dvec3(0.0) || m.transmit != dvec3(0.0);
        emits = emits || m.emission != dvec3(0.0);
    }
    std::uint64_t queries = 0;
    if (s.render.mode == RenderMode::Global) {
        const std::uint64_t rays = s.render.max_bounces + 1u;
        const bool emitters = emits || s.environment.has_value();
        queries = rays * (1u + s.lights.size() + (emitters && s.render.nee ? 1u : 0u));
    } else {
        const std::uint64_t rays = secondary ? s.render.max_depth + 1u : 1u;
        queries = rays * (1u + s.lights.size() + (emits ? s.render.light_samples : 0u));
    }
    return queries * (primitives + 6u) <= kernel::DEFAULT_LOOP_BUDGET;
}

Scene with_grid(Scene s, GridMode mode) {
    s.render.grid.mode = mode;
    return s;
}

// A 4-unit cluster (`objects`, JSON objects each followed by a comma) on a floor of
// two triangles 200 wide, one light with shadows, 64x48: the scenes of the tests of
// what the grid leaves out.
Scene cluster_on_a_floor(const char* name, const std::string& objects) {
    return test::scene_from_text(name, R"({
      "camera": {"eye": [0, 6, 9], "look_at": [0, 1, 0], "fov": 45, "width": 64, "height": 48},
      "render": {"shadows": true},
      "materials": {"m": {"diffuse": [0.8, 0.6, 0.4], "kd": 1, "ks": 0.3, "shininess": 20}},
      "lights": [{"type": "point", "position": [4, 10, 6], "intensity": 1}],
      "objects": [)" + objects + R"(
        {"type": "triangle", "vertices": [[-100, 0, -100], [100, 0, -100], [100, 0, 100]], "material": "m"},
        {"type": "triangle", "vertices": [[-100, 0, -100], [100, 0, 100], [-100, 0, 100]], "material": "m"}
      ]})");
}

// 48 small triangles in the cluster, each with a sphere beside it of radius
// sphere_radius + radius_step * i when sphere_radius is above zero: objects for
// cluster_on_a_floor.
std::string triangles_and_spheres(double sphere_radius, double radius_step = 0.0) {
    std::string objects;
    for (int i = 0; i < 48; ++i) {
        const double x = -1.5 + (i % 4), y = 0.4 + (i / 16), z = -1.5 + (i / 4 % 4);
        objects += fmt::format(R"({{"type": "triangle", "vertices": [[{}, {}, {}], [{}, {}, {}], [{}, {}, {}]],
                                   "material": "m"}},)",
                               x - 0.3, y, z, x + 0.3, y, z + 0.1, x, y + 0.4, z - 0.2);
        if (sphere_radius > 0.0) {
            objects += fmt::format(R"({{"type": "sphere", "center": [{}, {}, {}], "radius": {}, "material": "m"}},)",
                                   x + 0.4, y + 0.3, z + 0.4, sphere_radius + radius_step * i);
        }
    }
    return objects;
}

// The scene with its grid gives brute force's image on both backends, with less than
// half of brute force's tests.
void expect_brute_forces_image(const Scene& scene) {
    const Scene brute = with_grid(scene, GridMode::Off);
    for (const bool vulkan : {false, true}) {
        const RenderOutcome grid = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
        const RenderOutcome none = vulkan ? test::render_vulkan(brute) : test::render_cpu(brute);
        test::expect_sane(grid);
        test::expect_sane(none);
        EXPECT_TRUE(grid.stats.grid.used);
        EXPECT_LE(compare_images(grid.image, none.image, 1e-5).max_abs, 1e-5) << (vulkan ? "vulkan" : "cpu");
        EXPECT_LT(grid.stats.intersection_tests, none.stats.intersection_tests / 2);
    }
}

class GridImage : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(GridImage, GridAndBruteForceGiveTheSameImage) {
    const Scene full = load_scene(GetParam());
    const std::size_t primitives = full.spheres.size() + full.triangles.size() + full.rings.size() +
                                   full.cylinders.size();
    const bool big = primitives > kBruteForceOnVulkanMax || !brute_force_fits_loop_budget(full, primitives);
    const Scene scene = big ? test::load_at_size(GetParam(), 32, 24) : test::load_at_size(GetParam(), 64, 48);

    Scene brute = with_grid(scene, GridMode::Off);
    brute.render.loop_budget = 0xFFFFFFFFu;  // the reference only: it has no iteration cap
    const RenderOutcome cpu_grid = test::render_cpu(with_grid(scene, GridMode::On));
    const RenderOutcome cpu_brute = test::render_cpu(brute);
    ASSERT_EQ(cpu_grid.stats.truncated_samples, 0u);
    ASSERT_EQ(cpu_brute.stats.truncated_samples, 0u);
    EXPECT_TRUE(cpu_grid.stats.grid.used);
    EXPECT_FALSE(cpu_brute.stats.grid.used);
    const ImageDiff cpu = compare_images(cpu_grid.image, cpu_brute.image, 1e-5);
    EXPECT_LE(cpu.max_abs, 1e-5) << "reference backend";
    // Same rays, same decisions, so the same shadow rays; far fewer tests.
    EXPECT_EQ(cpu_grid.stats.shadow_rays, cpu_brute.stats.shadow_rays);

    const RenderOutcome gpu_grid = test::render_vulkan(with_grid(scene, GridMode::On));
    ASSERT_EQ(gpu_grid.stats.truncated_samples, 0u);
    std::printf("%s: %zu primitives, grid %ux%ux%u, tests per ray %.1f (grid) vs %.1f (brute force), "
                "max abs grid vs brute: cpu %.3g",
                GetParam().filename().c_str(), primitives, cpu_grid.stats.grid.resolution[0],
                cpu_grid.stats.grid.resolution[1], cpu_grid.stats.grid.resolution[2],
                cpu_grid.stats.per_ray(cpu_grid.stats.intersection_tests),
                cpu_brute.stats.per_ray(cpu_brute.stats.intersection_tests), cpu.max_abs);
    if (!big) {
        const RenderOutcome gpu_brute = test::render_vulkan(with_grid(scene, GridMode::Off));
        ASSERT_EQ(gpu_brute.stats.truncated_samples, 0u);
        const ImageDiff gpu = compare_images(gpu_grid.image, gpu_brute.image, 1e-5);
        std::printf(", vulkan %.3g\n", gpu.max_abs);
        EXPECT_LE(gpu.max_abs, 1e-5) << "Vulkan backend";
    } else {
        // Lavapipe cannot trace this scene by brute force (its loop cap), so Vulkan's
        // grid image is held to the reference's brute force instead, at the same
        // 1e-5: the two backends' float results agree that closely here (6e-7 at most
        // on the shipped scenes, 2026-12-02).
        const ImageDiff cross = compare_images(gpu_grid.image, cpu_brute.image, 1e-5);
        std::printf(", vulkan grid vs cpu brute force %.3g\n", cross.max_abs);
        EXPECT_LE(cross.max_abs, 1e-5) << "Vulkan grid against the reference's brute force";
    }
}

// A kind with fewer primitives than the threshold is left out of the grid's cells and
// tested once per ray among its loose primitives (flatten/flat_scene.cpp, loose_kinds): here
// a floor quad 200 wide, a ring and a cylinder beside 48 spheres in a 4-unit
// cluster. The grid's box is then the cluster's, not the floor's, and the image is
// brute force's on both backends.
TEST(GridKinds, FewOfAKindAreTestedOutsideTheGrid) {
    std::string spheres;
    for (int i = 0; i < 48; ++i) {
        spheres += fmt::format(R"({{"type": "sphere", "center": [{}, {}, {}], "radius": 0.3, "material": "m"}},)",
                               -1.5 + (i % 4), 0.4 + (i / 16), -1.5 + (i / 4 % 4));
    }
    const Scene scene = cluster_on_a_floor("grid_kinds", spheres + R"(
        {"type": "ring", "center": [3, 0.01, 2], "normal": [0, 1, 0], "inner": 0.2, "outer": 0.8, "material": "m"},
        {"type": "cylinder", "base": [-3, 0, 2], "top": [-3, 1.5, 2], "radius": 0.4, "capped": true, "material": "m"},)");
    const FlatScene gpu = flatten_scene(scene, AccelPolicy{32, 0xFFFFFFFFu});
    ASSERT_TRUE(gpu.grid.used);
    EXPECT_TRUE(gpu.features.has(Feature::GRID_SPHERES));
    EXPECT_FALSE(gpu.features.has(Feature::GRID_TRIANGLES));
    EXPECT_FALSE(gpu.features.has(Feature::GRID_RINGS));
    EXPECT_FALSE(gpu.features.has(Feature::GRID_CYLINDERS));
    EXPECT_TRUE(gpu.features.has(Feature::LOOSE_TRIANGLES));
    EXPECT_TRUE(gpu.features.has(Feature::LOOSE_RINGS));
    EXPECT_TRUE(gpu.features.has(Feature::LOOSE_CYLINDERS));
    EXPECT_FALSE(gpu.features.has(Feature::LOOSE_SPHERES));
    EXPECT_EQ(gpu.grid.outside, (std::vector<std::string>{"triangles: 2", "rings: 1", "cylinders: 1"}));
    EXPECT_NE(gpu.grid.reason.find("tested per ray, outside the grid"), std::string::npos) << gpu.grid.reason;
    // The loose references first, grouped by kind; the cells list spheres only.
    ASSERT_EQ(gpu.grid_nodes[0], 4u);
    EXPECT_EQ(std::vector<std::uint32_t>(gpu.grid_refs.begin(), gpu.grid_refs.begin() + 4),
              (std::vector<std::uint32_t>{kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT,
                                          (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | 1u,
                                          kernel::REF_RING << kernel::REF_KIND_SHIFT,
                                          kernel::REF_CYLINDER << kernel::REF_KIND_SHIFT}));
    ASSERT_GE(gpu.grid_refs.size(), 4u + 48u);
    for (std::size_t i = 4; i < gpu.grid_refs.size(); ++i) {
        EXPECT_EQ(gpu.grid_refs[i] >> kernel::REF_KIND_SHIFT, kernel::REF_SPHERE) << "only spheres are listed";
    }
    // The box holds the cluster (x from -1.8 to 1.8), not the floor (x from -100 to 100).
    EXPECT_GT(kernel::grid_min(gpu.params).x + gpu.origin.x, -2.0f);
    EXPECT_LT(kernel::grid_max(gpu.params).x + gpu.origin.x, 2.0f);

    // Partials rendered with and without the grid still merge (render/fingerprint.hpp).
    EXPECT_EQ(scene_fingerprint(gpu),
              scene_fingerprint(flatten_scene(with_grid(scene, GridMode::Off), AccelPolicy{32, 0xFFFFFFFFu})));
    expect_brute_forces_image(scene);
}

// A primitive whose box would stretch the grid's far beyond the rest is left loose
// (host/accel/grid.cpp, choose_stretching) even when its kind is listed: here a floor of
// two triangles 200 wide under 48 small triangles and 48 spheres in a 4-unit
// cluster. The grid's box is the cluster's, the floor is tested once per ray from
// the references before cell 0's, and the image is brute force's on both backends.
TEST(GridLoose, AFloorUnderAClusterIsTestedPerRay) {
    const Scene scene = cluster_on_a_floor("grid_loose", triangles_and_spheres(0.2));
    const FlatScene gpu = flatten_scene(scene, AccelPolicy{32, 0xFFFFFFFFu});
    ASSERT_TRUE(gpu.grid.used);
    EXPECT_TRUE(gpu.features.has(Feature::GRID_TRIANGLES));
    EXPECT_TRUE(gpu.features.has(Feature::LOOSE_TRIANGLES));
    EXPECT_FALSE(gpu.features.has(Feature::LOOSE_SPHERES));
    EXPECT_EQ(gpu.grid.outside, (std::vector<std::string>{"triangles: 2 of 50"}));
    ASSERT_EQ(gpu.grid_nodes[0], 2u);
    EXPECT_EQ(gpu.grid_refs[0], (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | 48u);
    EXPECT_EQ(gpu.grid_refs[1], (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | 49u);
    // The box holds the cluster (x from -1.8 to 2.1), not the floor (x from -100 to 100).
    EXPECT_GT(kernel::grid_min(gpu.params).x + gpu.origin.x, -2.0f);
    EXPECT_LT(kernel::grid_max(gpu.params).x + gpu.origin.x, 2.3f);

    EXPECT_EQ(scene_fingerprint(gpu),
              scene_fingerprint(flatten_scene(with_grid(scene, GridMode::Off), AccelPolicy{32, 0xFFFFFFFFu})));
    // A resolution from the scene asks for a grid over everything.
    Scene given = scene;
    given.render.grid.resolution = {8, 8, 8};
    const FlatScene everything = flatten_scene(given, AccelPolicy{32, 0xFFFFFFFFu});
    EXPECT_FALSE(everything.features.has(Feature::LOOSE_TRIANGLES));
    EXPECT_EQ(everything.grid_nodes[0], 0u);
    expect_brute_forces_image(scene);
}

// 48 small spheres in the cells and, behind the cluster, a large one the grid leaves
// loose because it would stretch the box: the loose sphere's position among the
// references is not its index, so a walk that confused the two would lose it.
TEST(GridSpheres, ALooseSphereListedAwayFromItsIndexRenders) {
    const Scene scene = cluster_on_a_floor("grid_spheres", triangles_and_spheres(0.1, 0.002) + R"(
        {"type": "sphere", "center": [0, -2, -20], "radius": 8, "material": "m"},)");
    const FlatScene gpu = flatten_scene(scene, AccelPolicy{32, 0xFFFFFFFFu});
    ASSERT_TRUE(gpu.grid.used);
    ASSERT_TRUE(gpu.features.has(Feature::GRID_SPHERES));
    bool loose_sphere_elsewhere = false;
    for (std::uint32_t i = 0; i < gpu.grid_nodes[0]; ++i) {
        const std::uint32_t ref = gpu.grid_refs[i];
        loose_sphere_elsewhere = loose_sphere_elsewhere ||
                                 ((ref >> kernel::REF_KIND_SHIFT) == kernel::REF_SPHERE &&
                                  (ref & kernel::REF_INDEX_MASK) != i);
    }
    EXPECT_TRUE(loose_sphere_elsewhere);
    expect_brute_forces_image(scene);
}

// Too few spheres for the cells: only the loose references hold spheres.
TEST(GridSpheres, OnlyLooseSpheresRender) {
    const Scene scene = cluster_on_a_floor("grid_loose_spheres", triangles_and_spheres(0.0) + R"(
        {"type": "sphere", "center": [-0.5, 1.2, 0.3], "radius": 0.35, "material": "m"},
        {"type": "sphere", "center": [0.9, 0.8, -0.6], "radius": 0.25, "material": "m"},)");
    const FlatScene gpu = flatten_scene(scene, AccelPolicy{32, 0xFFFFFFFFu});
    ASSERT_TRUE(gpu.grid.used);
    ASSERT_FALSE(gpu.features.has(Feature::GRID_SPHERES));
    ASSERT_TRUE(gpu.features.has(Feature::LOOSE_SPHERES));
    expect_brute_forces_image(scene);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GridImage, ::testing::ValuesIn(vkrt::test::repo_scenes()), test::scene_test_name);

}  // namespace
