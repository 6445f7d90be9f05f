// The numerical-stability suite's common invariant (docs/numerics.md): every
// stability scene renders with no NaN or infinite pixel. Every scene under
// tests/scenes/stability/ (one or more per case of the suite, named
// caseN_*.json) is rendered as it is on both backends: no pixel may be NaN or
// infinite, no sample may have been discarded as non-finite or truncated by the loop
// budget, and the Vulkan run must raise no validation message. The cases' own tests
// (the other files of tests/stability/) check what each scene is about; this one
// guards the invariant that must hold for all of them, including scenes added later.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "image/compare.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> stability_scenes() {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(fs::path(VKRT_SOURCE_DIR) / "tests/scenes/stability")) {
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

TEST(StabilityScenes, EveryCaseHasAScene) {
    // At least one scene per case that has scenes (cases 1-10 and 12; case 11 is the
    // random numbers, probed directly in probe/float_profile_test).
    for (int c = 1; c <= 12; ++c) {
        if (c == 11) continue;
        const auto files = stability_scenes();
        const bool found = std::any_of(files.begin(), files.end(), [&](const fs::path& f) {
            const std::string stem = f.stem().string();
            const std::string prefix = "case" + std::to_string(c) + "_";
            return stem.rfind(prefix, 0) == 0;
        });
        EXPECT_TRUE(found) << "no scene for case " << c << " in tests/scenes/stability/";
    }
}

class StabilityScene : public ::testing::TestWithParam<fs::path> {};

TEST_P(StabilityScene, FiniteOnBothBackends) {
    const Scene scene = load_scene(GetParam());
    // Kept small so that the suite stays fast on lavapipe in CI.
    ASSERT_LE(std::uint64_t(scene.camera.width) * scene.camera.height, 64u * 48u) << "stability scenes are 64x48 at most";
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome vulkan = test::render_vulkan(scene);
    for (const RenderOutcome* out : {&cpu, &vulkan}) {
        const char* name = out == &cpu ? "cpu" : "vulkan";
        EXPECT_EQ(test::nonfinite_values(out->image), 0u) << name;
        EXPECT_EQ(out->stats.nonfinite_samples, 0u) << name << ": samples discarded as NaN/Inf";
        EXPECT_EQ(out->stats.truncated_samples, 0u) << name << ": samples stopped by the loop budget";
    }
    EXPECT_EQ(vulkan.stats.validation_messages, 0u);
    const ImageDiff d = compare_images(vulkan.image, cpu.image, 1e-3);
    std::printf("%s: %zu of %zu pixels differ by more than 1e-3 between the backends, max abs %.3g\n",
                GetParam().filename().c_str(), d.pixels_over, d.pixels, d.max_abs);
}

INSTANTIATE_TEST_SUITE_P(Scenes, StabilityScene, ::testing::ValuesIn(stability_scenes()), test::scene_test_name);

}  // namespace
}  // namespace vkrt
