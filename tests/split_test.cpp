// Split-invariant sampling (DESIGN.md principle 4): rendering samples [0, 5) in one
// run, or [0, 2) and [2, 5) in two and adding the results, traces the same rays.
// Counters agree exactly; radiance sums agree up to the rounding of the final merge.
#include <gtest/gtest.h>

#include <cmath>

#include "gpu/vulkan_backend.hpp"
#include "ref/ref_backend.hpp"
#include "scene/scene_gpu.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;

void expect_split_invariant(Backend& backend) {
    // Jittered antialiasing, so every sample index draws different random numbers.
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "spheres_triangles.json", 32, 24);
    const SceneGpu gpu = build_scene_gpu(scene);
    ASSERT_TRUE(gpu.features.has(Feature::HAS_JITTER));

    const RenderResult whole = backend.render(gpu, SampleRange{0, 5});
    const RenderResult first = backend.render(gpu, SampleRange{0, 2});
    const RenderResult rest = backend.render(gpu, SampleRange{2, 3});
    ASSERT_EQ(whole.accum.size(), first.accum.size());

    double largest_relative = 0.0;
    for (std::size_t p = 0; p < whole.accum.size(); ++p) {
        const glm::vec4 merged = first.accum[p] + rest.accum[p];
        EXPECT_EQ(merged.a, whole.accum[p].a) << "pixel " << p;
        EXPECT_EQ(first.counters[p] + rest.counters[p], whole.counters[p]) << "pixel " << p;
        for (int c = 0; c < 3; ++c) {
            const double diff = std::abs(double(merged[c]) - double(whole.accum[p][c]));
            const double relative = diff / std::max(1e-3, std::abs(double(whole.accum[p][c])));
            largest_relative = std::max(largest_relative, relative);
        }
    }
    // A merge adds one rounding of at most half an ULP to sums that agree otherwise.
    EXPECT_LE(largest_relative, 1e-6);

    // And the pieces really differ: a split that rendered the same samples twice
    // would have the right counts but not the right sums.
    std::size_t differing = 0;
    for (std::size_t p = 0; p < whole.accum.size(); ++p) {
        if (std::abs(first.accum[p].r / 2.0f - rest.accum[p].r / 3.0f) > 1e-4f) ++differing;
    }
    EXPECT_GT(differing, 10u);
}

TEST(Split, ReferenceBackend) {
    auto backend = make_reference_backend();
    expect_split_invariant(*backend);
}

TEST(Split, VulkanBackend) {
    auto backend = make_vulkan_backend(VulkanOptions{"", true});
    expect_split_invariant(*backend);
    EXPECT_EQ(backend->validation_messages(), 0u);
}

}  // namespace
