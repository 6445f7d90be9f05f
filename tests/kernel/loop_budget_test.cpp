// The kernel's own loop budget must fire, on both backends, before lavapipe's
// silent 65,535-iteration cap would: a brute-force scene with more spheres than the
// budget truncates every sample that loops over them, and says so.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;

// 8x8 pixels; the camera looks at a row of spheres, all of which every eye ray tests
// (brute force: the grid would spare most of the tests).
Scene too_many_spheres(std::uint32_t count) {
    Scene s;
    s.render.grid.mode = GridMode::Off;
    s.camera.eye = {0, 0, 10};
    s.camera.look_at = {0, 0, 0};
    s.camera.width = 8;
    s.camera.height = 8;
    Material m;
    m.diffuse = {1, 1, 1};
    s.materials.push_back(m);
    for (std::uint32_t i = 0; i < count; ++i) {
        s.spheres.push_back(Sphere{{double(i % 100) * 0.01, double(i / 100) * 0.01, -5.0}, 0.004, 0});
    }
    return s;
}

void expect_truncation(const RenderOutcome& out, std::uint64_t expected) {
    EXPECT_EQ(out.stats.truncated_samples, expected);
}

TEST(LoopBudget, FiresOnBothBackendsWhenOverBudget) {
    const Scene scene = too_many_spheres(61000);  // > DEFAULT_LOOP_BUDGET tests per eye ray
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome gpu = test::render_vulkan(scene);
    expect_truncation(cpu, 64);
    expect_truncation(gpu, 64);
    EXPECT_EQ(gpu.stats.validation_messages, 0u);
}

TEST(LoopBudget, SilentWhenUnderBudget) {
    const Scene scene = too_many_spheres(2000);
    expect_truncation(test::render_cpu(scene), 0);
    const RenderOutcome gpu = test::render_vulkan(scene);
    expect_truncation(gpu, 0);
}

TEST(LoopBudget, CountsEveryIterationAndEveryLoopEntry) {
    // 100 spheres and no lights: the eye ray's sphere loop costs 100 iterations plus
    // one for its exit test, the way lavapipe counts, and, with 100 spheres
    // (DEFERRED_SPHERES), two more loops run once each (traversal.glsl): the passes
    // around it, and the deferred spheres' tests after it, whose body runs masked
    // when no lane has any. So 103 is exactly enough.
    Scene scene = too_many_spheres(100);
    scene.render.loop_budget = 103;
    expect_truncation(test::render_cpu(scene), 0);
    expect_truncation(test::render_vulkan(scene), 0);
    scene.render.loop_budget = 102;
    expect_truncation(test::render_cpu(scene), 64);
    expect_truncation(test::render_vulkan(scene), 64);
}

// One sphere lit by many lights with shadows: each light costs its own iteration plus
// a shadow ray's one-sphere loop, entry included: three counts a light (one sphere
// is too few for DEFERRED_SPHERES, whose loops would add two). Lavapipe cut 22,000
// lights silently before shadow-ray loop entries were counted.
Scene many_lights(std::uint32_t count) {
    Scene s = too_many_spheres(0);
    s.camera.width = 4;
    s.camera.height = 4;
    s.spheres.push_back(Sphere{{0, 0, 0}, 6.0, 0});  // fills the view
    for (std::uint32_t i = 0; i < count; ++i) {
        const double a = double(i) * 0.618;
        s.lights.push_back(Light{{10 * std::cos(a), 10 * std::sin(a), 10}, {1, 1, 1}, 1e-5});
    }
    return s;
}

TEST(LoopBudget, ShadowRayLoopsCountToo) {
    const Scene over = many_lights(21000);  // 3 * 21,000 > 60,000
    expect_truncation(test::render_cpu(over), 16);
    expect_truncation(test::render_vulkan(over), 16);

    const Scene under = many_lights(19000);  // 3 * 19,000 + 3 < 60,000: every sample complete
    const RenderOutcome cpu = test::render_cpu(under);
    const RenderOutcome gpu = test::render_vulkan(under);
    expect_truncation(cpu, 0);
    expect_truncation(gpu, 0);
    for (std::size_t i = 0; i < cpu.image.rgb.size(); ++i) {
        EXPECT_NEAR(gpu.image.rgb[i], cpu.image.rgb[i], 1e-4) << "value " << i;
    }
    EXPECT_GT(cpu.image.pixel(2, 2)[0], 0.05f);  // lit, so a silent cut would show
}

// lavapipe counts loop iterations per 8-lane vector over the whole shader run, the
// budget per invocation: SPD balls by brute force with its reflections, whose lanes
// branch through the ray tree differently, passes lavapipe's cap in vectors where no
// lane passes the budget. Those samples must be flagged, not added to the image with
// loops cut short: every sample the reference truncates (its lanes are alone) is
// truncated on Vulkan too, and more, since a vector's count is at least each of its
// lanes'. Before driver_cut_loops() Vulkan flagged 6 samples here against the
// reference's 190, and traced 1,410 reflection rays against 1,537.
TEST(LoopBudget, LoopsTheDriverCutAreFlaggedToo) {
    Scene scene = load_scene(test::source_dir() / "scenes" / "spd" / "balls.nff.gz");
    scene.render.grid.mode = GridMode::Off;
    scene.camera.width = 48;
    scene.camera.height = 48;
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome gpu = test::render_vulkan(scene);
    ASSERT_GT(cpu.stats.truncated_samples, 0u) << "the scene no longer reaches the budget";
    EXPECT_GE(gpu.stats.truncated_samples, cpu.stats.truncated_samples);
}

TEST(LoopBudget, CommandLineReportsTruncationAsAnError) {
    // Rendering through the program: non-zero exit and a message that says why.
    const auto dir = test::temp_dir("budget_test");
    const auto scene = dir / "budget.json";
    std::ofstream(scene) << R"({
        "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "width": 4, "height": 4},
        "render": {"loop_budget": 2},
        "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},
                    {"type": "sphere", "center": [3, 0, 0], "radius": 1, "material": "m"},
                    {"type": "sphere", "center": [-3, 0, 0], "radius": 1, "material": "m"}]})";
    const test::ProgramRun run = test::run_vkrt(
        "render " + test::shell_quote(scene.string()) + " -q --backend cpu -o " + test::shell_quote((dir / "out.png").string()),
        dir);
    EXPECT_EQ(run.code, 1);
    EXPECT_NE(run.stderr_text.find("16 samples ran out of the per-invocation loop budget"), std::string::npos)
        << run.stderr_text;
}

}  // namespace
