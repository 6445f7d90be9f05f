// The numerical-stability suite (docs/numerics.md), case 6: the uniform grid where 3D-DDA implementations classically break,
// on both backends. The case list, each sub-case with the tests that prove it
// ("here": this file; the scenes are tests/scenes/stability/case6_*.json):
//
// 6.1 Axis-aligned directions with +0 and -0 components visit the same cells.
//     GridTraversal.AxisRaysWithPlusAndMinusZeroVisitTheSameCells (a cell count);
//     here SignedZeroRaysWalkTheSameCells (the visited cell sequence and the hit of
//     every +0/-0 variant of axis-aligned and in-plane rays, reference kernel) and
//     SignedZeroLightGivesTheSameImageAndCells (shadow rays with +0 or -0
//     components, both backends: cells visited, tests, image).
// 6.2 Origins exactly on grid faces, edges and corners.
//     GridTraversal.OriginsOnFacesEdgesAndCornersOfTheGridAndItsCells (14 origins x
//     63 directions, reference kernel); here EyeOnGridBoundary (the camera on the
//     grid box's corners, an edge and a face, and on an inner cell corner, edge and
//     face, every eye ray starting there; both backends, grid = brute force).
// 6.3 Flat scenes. GridResolution.FlatAxesGetOneCellAndLeaveTheBudgetToTheOthers,
//     GridBuild.FlatSceneAndSinglePrimitive (the build); here case6_flat_plane,
//     case6_flat_edge_on (eye rays lying in the plane), case6_one_quad.
// 6.4 One cell: here case6_one_cell (resolution 1x1x1, every primitive kind).
// 6.5 All primitives in one cell: here case6_teapot_in_stadium and
//     TeapotInStadiumDoesNotDegenerate.
// 6.6 Resolutions beyond the limits. GridBuild.RequestedResolutionIsUsedAndClamped
//     ToTheDeviceLimit, GridBuild.TheHostLimitsCellsWhateverTheDeviceAllows (the
//     builder's note); here ResolutionBeyondTheLimit* (the loader's refusal above
//     65536 per axis, the reduction of 65536^3 in the stats and as a warning on
//     stderr) and case6_resolution_beyond_limit.
// 6.7 Termination for zero, NaN and infinite direction components.
//     GridTraversal.NonFiniteRaysTerminateWithoutAHit,
//     GridTraversal.WalkEndsWithinTheCellsOfTheGrid; here
//     SignedZeroRaysWalkTheSameCells bounds every walk by nx + ny + nz cells.
// 6.8 Grid results equal brute force in every case: here GridEqualsBruteForce, every
//     case6_*.json on both backends, max abs difference 0 (not merely <= 1e-5).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "kernel/kernel.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

namespace kernel = vkrt::kernel;
using kernel::Kernel;
using kernel::vec3;

const std::filesystem::path kCases = std::filesystem::path(VKRT_SOURCE_DIR) / "tests/scenes/stability";

Scene with_grid_off(Scene s) {
    s.render.grid.mode = GridMode::Off;
    return s;
}

// Renders a scene as it asks (its grid on) and by brute force on one backend, and
// requires the same image, bit for bit; returns the grid render.
RenderOutcome expect_grid_equals_brute_force(const Scene& scene, bool vulkan, float* difference = nullptr) {
    const auto render = vulkan ? test::render_vulkan : test::render_cpu;
    const RenderOutcome grid = render(scene);
    const RenderOutcome brute = render(with_grid_off(scene));
    test::expect_sane(grid);
    test::expect_sane(brute);
    EXPECT_TRUE(grid.stats.grid.used) << grid.stats.grid.reason;
    EXPECT_FALSE(brute.stats.grid.used);
    const float worst = test::max_abs_difference(grid.image, brute.image);
    EXPECT_EQ(worst, 0.0f) << (vulkan ? "Vulkan" : "reference") << " backend";
    EXPECT_EQ(grid.stats.eye_hits, brute.stats.eye_hits);
    EXPECT_EQ(grid.stats.shadow_rays, brute.stats.shadow_rays);
    if (difference) *difference = worst;
    return grid;
}

// ------------------------------------------------ 6.8: every case scene, both ways

std::vector<std::filesystem::path> case6_scenes() {
    std::vector<std::filesystem::path> out;
    for (const auto& entry : std::filesystem::directory_iterator(kCases)) {
        if (entry.path().filename().string().rfind("case6_", 0) == 0) out.push_back(entry.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

class GridEqualsBruteForce : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(GridEqualsBruteForce, OnBothBackends) {
    const Scene scene = load_scene(GetParam());
    float cpu_difference = 0.0f, vulkan_difference = 0.0f;
    const RenderOutcome cpu = expect_grid_equals_brute_force(scene, false, &cpu_difference);
    const RenderOutcome vulkan = expect_grid_equals_brute_force(scene, true, &vulkan_difference);
    EXPECT_EQ(cpu.stats.grid.resolution, vulkan.stats.grid.resolution);
    std::printf("%s: grid %ux%ux%u, %llu references, %.2f cells and %.2f tests per ray; max abs grid - brute "
                "force: reference %g, Vulkan %g\n",
                GetParam().filename().c_str(), cpu.stats.grid.resolution[0], cpu.stats.grid.resolution[1],
                cpu.stats.grid.resolution[2], static_cast<unsigned long long>(cpu.stats.grid.references),
                cpu.stats.per_ray(cpu.stats.cells_visited), cpu.stats.per_ray(cpu.stats.intersection_tests),
                double(cpu_difference), double(vulkan_difference));
}

INSTANTIATE_TEST_SUITE_P(Case6, GridEqualsBruteForce, ::testing::ValuesIn(case6_scenes()), test::scene_test_name);

// --------------------------------------------------------------- 6.1: signed zeros

// A cell plane exactly as the walk computes it (grid.glsl: grid_min + k * grid_cell,
// in float).
float cell_plane(const kernel::Params& p, int axis, int k) {
    return kernel::grid_min(p)[axis] + float(k) * kernel::grid_cell(p)[axis];
}


using Cells = std::vector<glm::ivec3>;

// The cells the kernel's walk visits along the whole ray, in order, to its end.
Cells walk(Kernel& k, const Kernel::Ray& ray, float t_max) {
    k.work_reset();
    Cells cells;
    Kernel::GridWalk w = k.grid_walk_start(ray, t_max);
    if (!w.inside) return cells;
    // A root cell's index: these grids are uniform (given resolutions are never split).
    auto cell = [](const Kernel::GridWalk& walk) { return glm::ivec3(walk.lo >> kernel::GRID_FRACTION_BITS); };
    cells.push_back(cell(w));
    while (k.grid_walk_step(ray, w)) cells.push_back(cell(w));
    return cells;
}

// The closest hit and the shadow answer, each a fresh invocation's (the loop budget
// counts per invocation); a query the budget cut short fails the test.
struct Answer {
    float t;
    std::uint32_t material;
    bool occluded;
    bool operator==(const Answer&) const = default;
};

Answer trace(Kernel& k, const Kernel::Ray& ray, float t_max) {
    k.work_reset();
    const Kernel::Hit hit = k.closest_hit(ray, t_max);
    EXPECT_FALSE(k.budget_exhausted());
    k.work_reset();
    const bool occluded = k.occluded(ray, t_max);
    EXPECT_FALSE(k.budget_exhausted());
    return Answer{hit.t, hit.t < t_max ? hit.material : 0u, occluded};
}

std::string describe(const Kernel::Ray& r) {
    return fmt::format("ray ({:.9g}, {:.9g}, {:.9g}) + t ({}, {}, {})", r.origin.x, r.origin.y, r.origin.z,
                       r.dir.x, r.dir.y, r.dir.z);
}

// Every way of replacing the zero components of `dir` by +0, -0, or a tiny value the
// walk must treat as zero (below GRID_PARALLEL, 1e-20): the smallest denormal, a
// denormal (which a device may flush) and a tiny normal float, of either sign.
std::vector<vec3> zero_like_variants(vec3 dir) {
    const float zero_like[] = {0.0f, -0.0f, 1e-45f, -1e-45f, 1e-40f, -1e-40f, 1e-25f, -1e-25f};
    std::vector<vec3> out{dir};
    for (int a = 0; a < 3; ++a) {
        if (dir[a] != 0.0f) continue;
        std::vector<vec3> next;
        for (const vec3& d : out) {
            for (float z : zero_like) {
                vec3 v = d;
                v[a] = z;
                next.push_back(v);
            }
        }
        out = next;
    }
    return out;
}

TEST(SignedZero, RaysWalkTheSameCells) {
    // The scene of the light twins: a forced 4x4x4 grid. Origins inside the grid,
    // outside it, and exactly on its faces and on inner cell planes; directions along
    // the axes and in the coordinate planes. Every variant of a ray (its zero
    // components +0, -0, denormal or tiny) must visit the same cells in the same order
    // and get the same closest hit and shadow answer, which must be brute force's.
    const Scene scene = load_scene(kCases / "case6_signed_zero_light_plus.json");
    const FlatScene gpu = flatten_scene(scene, AccelPolicy{});
    Kernel grid = make_kernel(gpu);
    Kernel brute = make_kernel(gpu);
    brute.HAS_GRID = false;
    const kernel::Params& p = gpu.params;
    const glm::uvec3 res = kernel::grid_resolution(p);

    std::mt19937 rng(6);
    std::uniform_real_distribution<float> inside(-3.2f, 3.2f);
    std::uniform_int_distribution<int> pick(0, 4);
    std::vector<vec3> origins;
    for (int i = 0; i < 400; ++i) {
        vec3 o(inside(rng), inside(rng) * 0.5f + 1.5f, inside(rng));
        // Snap some coordinates onto a cell plane (0 and res: the grid's faces).
        for (int a = 0; a < 3; ++a) {
            const int k = pick(rng);
            if (k <= int(res[a]) && i % 3 != 0) o[a] = cell_plane(p, a, k);
        }
        origins.push_back(o);
    }
    std::vector<vec3> dirs;
    for (int a = 0; a < 3; ++a) {
        for (float s : {1.0f, -1.0f}) {
            vec3 d(0.0f);
            d[a] = s;
            dirs.push_back(d);  // along an axis: two zero components
            vec3 tilted = d;
            tilted[(a + 1) % 3] = 0.37f * s;
            dirs.push_back(glm::normalize(tilted));  // in a coordinate plane: one
        }
    }
    int rays = 0, walks_compared = 0, failures = 0;
    std::size_t longest = 0;
    for (const vec3& o : origins) {
        for (const vec3& d : dirs) {
            for (float t_max : {kernel::INFINITY_T, 2.5f}) {
                const std::vector<vec3> variants = zero_like_variants(d);
                const Kernel::Ray first(o, variants[0]);
                const Cells cells = walk(grid, first, t_max);
                const Answer answer = trace(grid, first, t_max);
                longest = std::max(longest, cells.size());
                ASSERT_LE(cells.size(), std::size_t(res.x + res.y + res.z)) << describe(first);
                const Answer want = trace(brute, first, t_max);
                if (!(answer == want)) {
                    ADD_FAILURE() << describe(first) << ": grid t " << answer.t << ", brute force t " << want.t;
                    ++failures;
                }
                for (std::size_t v = 1; v < variants.size(); ++v) {
                    const Kernel::Ray ray(o, variants[v]);
                    ++walks_compared;
                    const Cells other = walk(grid, ray, t_max);
                    const Answer other_answer = trace(grid, ray, t_max);
                    // +0 and -0 make the same ray, so the same answer. A tiny component
                    // makes another ray, which may leave a primitive's exact edge that
                    // the zero one touches: its answer must be brute force's own.
                    const bool exact_zeros = glm::all(glm::equal(ray.dir, first.dir));
                    const Answer other_want = exact_zeros ? answer : trace(brute, ray, t_max);
                    if (other != cells || !(other_answer == other_want)) {
                        ADD_FAILURE() << describe(ray) << " walks " << other.size() << " cells (t " << other_answer.t
                                      << ", want " << other_want.t << "), " << describe(first) << " walks "
                                      << cells.size() << " (t " << answer.t << ")";
                        ++failures;
                    }
                }
                ++rays;
                if (failures > 10) FAIL() << "too many failures";
            }
        }
    }
    std::printf("%d rays, %d variants with other zero-like components compared with them, longest walk %zu "
                "cells (grid %ux%ux%u)\n",
                rays, walks_compared, longest, res.x, res.y, res.z);
}

TEST(SignedZero, LightGivesTheSameImageAndCells) {
    // The light at (+0, 6, +0), (-0, 6, -0) or (-1e-40, 6, -1e-40): the shadow rays of
    // the centre column and row (whose hits have x = +0 or z = +0 exactly, on a cell
    // plane) carry +0, -0 or denormal components.
    const Scene plus = load_scene(kCases / "case6_signed_zero_light_plus.json");
    const std::vector<std::string> twins = {"minus", "denormal"};
    {
        // The premises, checked: x = 0 and z = 0 are cell planes; the centre pixel's
        // eye ray runs straight down and hits the floor at x = z = +0, so its shadow
        // ray toward each twin's light has the components named.
        const FlatScene gpu = flatten_scene(plus, AccelPolicy{});
        ASSERT_EQ(cell_plane(gpu.params, 0, 2), 0.0f);
        ASSERT_EQ(cell_plane(gpu.params, 2, 2), 0.0f);
        Kernel k = make_kernel(gpu);
        const Kernel::Ray eye = k.camera_ray(16.5f, 16.5f);
        ASSERT_EQ(eye.dir, vec3(0.0f, -1.0f, 0.0f));
        const float t = trace(k, eye, kernel::INFINITY_T).t;
        const vec3 p = eye.origin + t * eye.dir;
        EXPECT_EQ(p, vec3(0.0f));
        const Scene minus = load_scene(kCases / "case6_signed_zero_light_minus.json");
        const Scene denormal = load_scene(kCases / "case6_signed_zero_light_denormal.json");
        const vec3 l_minus = vec3(flatten_scene(minus, AccelPolicy{}).lights.at(0).position) - p;
        const vec3 l_denormal = vec3(flatten_scene(denormal, AccelPolicy{}).lights.at(0).position) - p;
        EXPECT_TRUE(std::signbit(l_minus.x) && l_minus.x == 0.0f && std::signbit(l_minus.z) && l_minus.z == 0.0f)
            << "the loader lost the sign of -0.0";
        EXPECT_EQ(std::fpclassify(l_denormal.x), FP_SUBNORMAL);
        EXPECT_EQ(std::fpclassify(l_denormal.z), FP_SUBNORMAL);
    }
    for (bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "Vulkan" : "reference");
        const auto render = vulkan ? test::render_vulkan : test::render_cpu;
        const RenderOutcome a = render(plus);
        test::expect_sane(a);
        std::printf("%s: %llu cells visited, %llu tests, %llu shadow rays with the +0 light\n",
                    vulkan ? "Vulkan" : "reference", static_cast<unsigned long long>(a.stats.cells_visited),
                    static_cast<unsigned long long>(a.stats.intersection_tests),
                    static_cast<unsigned long long>(a.stats.shadow_rays));
        for (const std::string& twin : twins) {
            SCOPED_TRACE(twin);
            const RenderOutcome b = render(load_scene(kCases / ("case6_signed_zero_light_" + twin + ".json")));
            test::expect_sane(b);
            EXPECT_EQ(a.stats.cells_visited, b.stats.cells_visited);
            EXPECT_EQ(a.stats.intersection_tests, b.stats.intersection_tests);
            EXPECT_EQ(a.stats.shadow_rays, b.stats.shadow_rays);
            EXPECT_EQ(test::max_abs_difference(a.image, b.image), 0.0f);
        }
    }
}

// ------------------------------------------- 6.2: the eye on the grid's boundaries

// Eight spheres at the corners of a cube, a triangle, a ring and a cylinder, on a
// forced 4x4x4 grid (cell planes near -2, -1, 0, 1, 2), with the eye at `eye`.
Scene boundary_scene(glm::dvec3 eye) {
    return test::scene_from_text("boundary", fmt::format(R"({{
      "camera": {{ "eye": [{}, {}, {}], "look_at": [0.1, 0.2, 0.05], "fov": 70, "width": 32, "height": 24 }},
      "render": {{ "grid": {{ "resolution": [4, 4, 4] }}, "ambient": [0.1, 0.1, 0.1] }},
      "materials": {{ "m": {{ "diffuse": [0.8, 0.6, 0.4], "specular": [1, 1, 1], "ks": 0.3 }} }},
      "lights": [ {{ "type": "point", "position": [0.5, 3, 2.5] }} ],
      "objects": [
        {{ "type": "sphere", "center": [-1.5, -1.5, -1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "sphere", "center": [-1.5, -1.5, 1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "sphere", "center": [-1.5, 1.5, -1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "sphere", "center": [-1.5, 1.5, 1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "sphere", "center": [1.5, -1.5, -1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "sphere", "center": [1.5, -1.5, 1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "sphere", "center": [1.5, 1.5, -1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "sphere", "center": [1.5, 1.5, 1.5], "radius": 0.5, "material": "m" }},
        {{ "type": "triangle", "vertices": [[-0.8, -0.6, -0.5], [0.7, -0.6, -0.7], [0.2, 0.6, -0.6]], "material": "m" }},
        {{ "type": "ring", "center": [0.5, 0.5, 0.6], "normal": [1, 1, 1], "inner": 0.2, "outer": 0.5, "material": "m" }},
        {{ "type": "cylinder", "base": [-0.5, -1, 0.5], "top": [-0.5, 0.8, 0.6], "radius": 0.25, "capped": true,
           "material": "m" }}
      ]
    }})", eye.x, eye.y, eye.z));
}

// Where the eye goes, from the kernel's grid parameters.
using Place = std::function<vec3(const kernel::Params&)>;

// The boundary scene with its eye exactly at `place`. The grid's padding depends on
// the eye's distance (GridRequest::eye), so the eye is moved and the grid rebuilt
// until the eye lies where asked on the grid it is rendered with.
Scene eye_at(const Place& place) {
    glm::dvec3 eye(0.3, 0.2, 0.1);
    for (int round = 0; round < 8; ++round) {
        const Scene s = boundary_scene(eye);
        const FlatScene gpu = flatten_scene(s, AccelPolicy{});
        const vec3 want = place(gpu.params);
        const vec3 got = kernel::camera_eye(gpu.params);
        if (got == want) return s;
        eye += glm::dvec3(want) - glm::dvec3(got);
    }
    ADD_FAILURE() << "the eye does not settle on the grid boundary";
    return boundary_scene(eye);
}

struct BoundaryCase {
    std::string name;
    Place place;
};

// gtest prints a parameter in the test's description (and ctest's test names): its
// name, not its bytes.
void PrintTo(const BoundaryCase& c, std::ostream* os) { *os << c.name; }

class EyeOnGridBoundary : public ::testing::TestWithParam<BoundaryCase> {};

TEST_P(EyeOnGridBoundary, GridEqualsBruteForceOnBothBackends) {
    const Scene scene = eye_at(GetParam().place);
    const kernel::Params p = flatten_scene(scene, AccelPolicy{}).params;
    const vec3 eye = kernel::camera_eye(p), lo = kernel::grid_min(p), hi = kernel::grid_max(p), cell = kernel::grid_cell(p);
    std::printf("eye (%.9g, %.9g, %.9g), grid (%.9g, %.9g, %.9g) to (%.9g, %.9g, %.9g), cells %.9g x %.9g x %.9g\n",
                eye.x, eye.y, eye.z, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, cell.x, cell.y, cell.z);
    const RenderOutcome cpu = expect_grid_equals_brute_force(scene, false);
    expect_grid_equals_brute_force(scene, true);
    EXPECT_GT(cpu.stats.eye_hits, 0u) << "the eye sees nothing: the case tests nothing";
}

INSTANTIATE_TEST_SUITE_P(
    Case6, EyeOnGridBoundary,
    ::testing::Values(
        BoundaryCase{"grid_corner_low", [](const kernel::Params& p) { return kernel::grid_min(p); }},
        BoundaryCase{"grid_corner_high", [](const kernel::Params& p) { return kernel::grid_max(p); }},
        BoundaryCase{"grid_edge_on_a_cell_plane",
                     [](const kernel::Params& p) { return vec3(kernel::grid_min(p).x, kernel::grid_max(p).y, cell_plane(p, 2, 2)); }},
        BoundaryCase{"grid_face_on_a_cell_edge",
                     [](const kernel::Params& p) {
                         return vec3(kernel::grid_max(p).x, cell_plane(p, 1, 1), cell_plane(p, 2, 3));
                     }},
        BoundaryCase{"grid_face", [](const kernel::Params& p) { return vec3(kernel::grid_min(p).x, 0.3f, -0.2f); }},
        BoundaryCase{"inner_cell_corner",
                     [](const kernel::Params& p) {
                         return vec3(cell_plane(p, 0, 2), cell_plane(p, 1, 2), cell_plane(p, 2, 2));
                     }},
        BoundaryCase{"inner_cell_edge",
                     [](const kernel::Params& p) { return vec3(cell_plane(p, 0, 1), cell_plane(p, 1, 3), 0.37f); }},
        BoundaryCase{"inner_cell_face",
                     [](const kernel::Params& p) { return vec3(0.21f, cell_plane(p, 1, 2), -0.33f); }}),
    [](const ::testing::TestParamInfo<BoundaryCase>& param) { return param.param.name; });

// ------------------------------------------------- 6.5: all in one cell, split

TEST(TeapotInStadium, DoesNotDegenerate) {
    // The room's extent sets the root cells; the cluster of 400 spheres falls into one,
    // which the builder splits, level after level, until the cluster's spheres are
    // apart. The walk must end every ray within the loop budget and make at most 30
    // tests per ray (brute force makes about 400), and the cells and references must
    // not blow up.
    const Scene scene = load_scene(kCases / "case6_teapot_in_stadium.json");
    const FlatScene gpu = flatten_scene(scene, AccelPolicy{});
    const std::size_t primitives = gpu.spheres.size() + gpu.triangles.size();
    // Which cells hold the cluster's spheres.
    std::vector<std::uint32_t> cluster_cells;
    const kernel::Params& p = gpu.params;
    for (const kernel::Sphere& s : gpu.spheres) {
        glm::uvec3 c;
        for (int a = 0; a < 3; ++a) {
            c[a] = std::uint32_t(std::floor((s.center_radius[a] - kernel::grid_min(p)[a]) / kernel::grid_cell(p)[a]));
        }
        const glm::uvec3 res = kernel::grid_resolution(p);
        cluster_cells.push_back((c.z * res.y + c.y) * res.x + c.x);
    }
    std::sort(cluster_cells.begin(), cluster_cells.end());
    cluster_cells.erase(std::unique(cluster_cells.begin(), cluster_cells.end()), cluster_cells.end());
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome brute = test::render_cpu(with_grid_off(scene));
    const RenderStats& s = cpu.stats;
    std::printf("%zu primitives; grid %ux%ux%u (root cells %.0f wide), %u levels of splits, %llu leaf cells, %llu "
                "references; the cluster's centres lie in %zu root cell(s); tests per ray %.1f (grid) vs %.1f (brute "
                "force), cells per ray %.2f\n",
                primitives, s.grid.resolution[0], s.grid.resolution[1], s.grid.resolution[2], double(kernel::grid_cell(p).x),
                s.grid.levels, static_cast<unsigned long long>(s.grid.cells),
                static_cast<unsigned long long>(s.grid.references), cluster_cells.size(),
                s.per_ray(s.intersection_tests), brute.stats.per_ray(brute.stats.intersection_tests),
                s.per_ray(s.cells_visited));
    test::expect_sane(cpu);
    EXPECT_LE(cluster_cells.size(), 2u) << "the scene no longer puts the cluster in one root cell";
    EXPECT_GE(s.grid.levels, 2u) << "the cluster's cell is not split";
    EXPECT_LE(s.per_ray(s.intersection_tests), 30.0);
    EXPECT_LE(s.grid.cells, 4u * primitives + 8u * 64u * 64u);
    EXPECT_LE(s.grid.references, 4u * s.grid.cells + primitives);
    EXPECT_LE(s.per_ray(s.cells_visited), 64.0);
}

// "uniform" (render.grid or --grid) keeps the paper's uniform grid: the same root
// cells, none split, the kernel's split walk left out, and the same image.
TEST(TeapotInStadium, UniformKeepsEveryCellWhole) {
    const Scene scene = load_scene(kCases / "case6_teapot_in_stadium.json");
    Scene uniform = scene;
    uniform.render.grid.mode = GridMode::Uniform;
    const FlatScene split = flatten_scene(scene, AccelPolicy{});
    const FlatScene whole = flatten_scene(uniform, AccelPolicy{});
    EXPECT_GE(split.grid.levels, 2u);
    EXPECT_TRUE(split.features.has(Feature::GRID_SPLIT));
    EXPECT_EQ(whole.grid.levels, 0u);
    EXPECT_FALSE(whole.features.has(Feature::GRID_SPLIT));
    EXPECT_EQ(whole.grid.resolution, split.grid.resolution);
    EXPECT_EQ(whole.grid_nodes.size(), std::size_t(whole.grid.resolution[0]) * whole.grid.resolution[1] *
                                               whole.grid.resolution[2] + 1);
    EXPECT_EQ(test::max_abs_difference(test::render_cpu(uniform).image, test::render_cpu(scene).image), 0.0f);
}

// ------------------------------------------------- 6.6: resolutions beyond limits

TEST(ResolutionBeyondTheLimit, AboveTheLoadersRangeIsRefusedNamingTheField) {
    try {
        test::scene_from_text("too_fine", R"({
          "camera": { "eye": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 8 },
          "render": { "grid": { "resolution": [100000, 100000, 100000] } },
          "materials": { "m": {} },
          "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ]
        })");
        FAIL() << "a resolution of 100000 per axis was accepted";
    } catch (const std::exception& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("render.grid.resolution[0]"), std::string::npos) << what;
        EXPECT_NE(what.find("65536"), std::string::npos) << what;
    }
}

TEST(ResolutionBeyondTheLimit, ReducedWithAWarningAndStillBruteForcesImage) {
    // 65536^3 cells (the most the loader accepts per axis) is 2^48: reduced to fit
    // vkrt's limit of 2^25 cells, said in the stats, and the image is brute force's.
    const Scene scene = load_scene(kCases / "case6_resolution_beyond_limit.json");
    for (bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "Vulkan" : "reference");
        const RenderOutcome out = expect_grid_equals_brute_force(scene, vulkan);
        const GridStats& g = out.stats.grid;
        EXPECT_LE(g.cells, std::uint64_t(1) << 25);
        EXPECT_GE(g.cells, std::uint64_t(1) << 24) << "reduced far more than the limit asks";
        // vkrt's limit on the reference; lavapipe's texel buffers hold 2^25 entries, so
        // there the device's limit (one entry fewer than vkrt's cells) comes first.
        const std::string limit = vulkan && g.reason.find("device") != std::string::npos
                                      ? "this device's buffer limit of "
                                      : "vkrt's limit of 33554432 cells";
        EXPECT_NE(g.reason.find("grid resolution 65536x65536x65536 exceeds " + limit), std::string::npos)
            << g.reason;
        EXPECT_EQ(g.warning, g.reason.substr(g.reason.find("grid resolution")));
        std::printf("%s: %s\n", vulkan ? "Vulkan" : "reference", g.reason.c_str());
    }
}

TEST(ResolutionBeyondTheLimit, TheProgramWarnsOnStandardError) {
    const std::filesystem::path dir = test::temp_dir("stability_grid_cli");
    const std::string scene = test::shell_quote((kCases / "case6_resolution_beyond_limit.json").string());
    const std::string out = test::shell_quote((dir / "out.png").string());
    // From the scene, and from the command line's --grid.
    for (const std::string& grid : {std::string("65536x65536x65536"), std::string("65536x1x65536")}) {
        const std::string extra = grid == "65536x65536x65536" ? "" : " --grid " + grid;
        const test::ProgramRun run = test::run_vkrt("render " + scene + " -o " + out + " --backend cpu" + extra, dir);
        EXPECT_EQ(run.code, 0) << run.stderr_text;
        EXPECT_NE(run.stderr_text.find("warning: grid resolution " + grid + " exceeds vkrt's limit of 33554432 "
                                       "cells; using "),
                  std::string::npos)
            << run.stderr_text;
    }
}

}  // namespace
}  // namespace vkrt
