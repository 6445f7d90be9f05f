// Split-invariant sampling (docs/architecture.md, principle 4): rendering samples [0, 5) in one
// run, or [0, 2) and [2, 5) in two and adding the results, traces the same rays.
// Sums (exact fixed point, kernel/sums.glsl) and counters agree bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "gpu/vulkan_backend.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/pixel_sums.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;

void expect_split_invariant(Backend& backend) {
    // Jittered antialiasing, so every sample index draws different random numbers.
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "spheres_triangles.json", 32, 24);
    const FlatScene gpu = flatten_scene(scene);
    ASSERT_TRUE(gpu.features.has(Feature::HAS_JITTER));

    const RenderResult whole = backend.render(gpu, SampleRange{0, 5});
    const RenderResult first = backend.render(gpu, SampleRange{0, 2});
    const RenderResult rest = backend.render(gpu, SampleRange{2, 3});
    ASSERT_EQ(whole.sums.size(), first.sums.size());
    for (std::size_t p = 0; p < whole.sums.size(); ++p) {
        ASSERT_EQ(kernel::add_sums(first.sums[p], rest.sums[p]), whole.sums[p]) << "pixel " << p;
        ASSERT_EQ(kernel::add_sums(rest.sums[p], first.sums[p]), whole.sums[p]) << "pixel " << p;
        ASSERT_EQ(first.counters[p] + rest.counters[p], whole.counters[p]) << "pixel " << p;
    }

    // And the pieces really differ: a split that rendered the same samples twice
    // would have the right counts but not the right sums.
    std::size_t differing = 0;
    for (std::size_t p = 0; p < whole.sums.size(); ++p) {
        if (std::abs(mean_radiance(first.sums[p]).r - mean_radiance(rest.sums[p]).r) > 1e-4f) ++differing;
    }
    EXPECT_GT(differing, 10u);
}

// A session renders pass after pass on the same pipeline and buffers: each pass
// returns its own samples alone (the sums buffer starts from zero every time), and
// the passes add up to the one-call render. A pass reports no set-up time of its
// own (the session paid it once); the session's is what its backend promises.
enum class SetupTime {
    None,      // the reference: nothing to set up, 0 exactly (cpu_backend.cpp)
    Measured,  // Vulkan: building the pipeline and uploading the scene, timed
};
void expect_session_passes_add_up(Backend& backend, SetupTime setup) {
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "spheres_triangles.json", 32, 24);
    const FlatScene gpu = flatten_scene(scene);
    const RenderResult whole = backend.render(gpu, SampleRange{0, 5});

    const std::unique_ptr<RenderSession> session = backend.begin(gpu);
    RenderResult total = session->render(SampleRange{0, 1});
    for (const SampleRange pass : {SampleRange{1, 1}, SampleRange{2, 3}}) {
        const RenderResult part = session->render(pass);
        EXPECT_EQ(part.setup_seconds, 0.0);
        for (std::size_t p = 0; p < part.sums.size(); ++p) {
            ASSERT_EQ(samples_summed(part.sums[p]), pass.count) << "pixel " << p;
            total.sums[p] = kernel::add_sums(total.sums[p], part.sums[p]);
            total.counters[p] = total.counters[p] + part.counters[p];
        }
    }
    EXPECT_EQ(total.sums, whole.sums);
    EXPECT_EQ(total.counters, whole.counters);
    const double setup_seconds = session->setup_seconds();
    if (setup == SetupTime::None) {
        EXPECT_EQ(setup_seconds, 0.0);
    } else {
        EXPECT_GT(setup_seconds, 0.0);
        EXPECT_TRUE(std::isfinite(setup_seconds)) << setup_seconds;
    }
}

TEST(Split, ReferenceBackend) {
    auto backend = make_cpu_backend();
    expect_split_invariant(*backend);
}

TEST(Split, ReferenceSessionPasses) {
    auto backend = make_cpu_backend();
    expect_session_passes_add_up(*backend, SetupTime::None);
}

TEST(Split, VulkanSessionPasses) {
    auto backend = make_vulkan_backend(VulkanOptions{"", true});
    expect_session_passes_add_up(*backend, SetupTime::Measured);
    EXPECT_EQ(backend->validation_messages(), 0u);
}

TEST(Split, VulkanBackend) {
    auto backend = make_vulkan_backend(VulkanOptions{"", true});
    expect_split_invariant(*backend);
    EXPECT_EQ(backend->validation_messages(), 0u);
}

}  // namespace
