// The numerical-stability suite (docs/numerics.md), case 12: instances. The colour
// box placed twice by an "instance" object, the second copy mirrored
// (tests/scenes/stability/case12_instances_unit.json), renders its own mirror image;
// the same scene at 1e-6 (case12_instances_tiny.json) renders the same 8-bit image,
// which needs ray offsets scaled to the scene (decision 0053); both backends.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "flatten/flat_scene.hpp"
#include "image/display.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

Scene stability_scene(const std::string& name) {
    return load_scene(std::filesystem::path(VKRT_SOURCE_DIR) / "tests/scenes/stability" / name);
}

long byte(float v) { return std::lround(linear_to_srgb(v) * 255.0f); }

// The share of pixels whose 8-bit colour in `a` equals that of `b`, read mirrored
// left to right when `mirror`.
double same_8bit(const Image& a, const Image& b, bool mirror) {
    std::size_t same = 0;
    for (std::uint32_t y = 0; y < a.height; ++y) {
        for (std::uint32_t x = 0; x < a.width; ++x) {
            const std::size_t p = std::size_t(y) * a.width + x;
            const std::size_t q = std::size_t(y) * b.width + (mirror ? b.width - 1 - x : x);
            bool equal = true;
            for (int c = 0; c < 3; ++c) equal = equal && byte(a.rgb[3 * p + c]) == byte(b.rgb[3 * q + c]);
            same += equal ? 1 : 0;
        }
    }
    return double(same) / double(std::size_t(a.width) * a.height);
}

RenderOutcome render(const Scene& scene, bool vulkan) {
    RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
    test::expect_sane(out);
    return out;
}

TEST(Instances, AMirroredCopyRendersTheMirrorImage) {
    const Scene scene = stability_scene("case12_instances_unit.json");
    for (bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "vulkan" : "cpu");
        const RenderOutcome out = render(scene, vulkan);
        const double same = same_8bit(out.image, out.image, true);
        fmt::print("{}: same 8-bit pixels as the mirror image {:.4f}%\n", vulkan ? "vulkan" : "cpu", 100.0 * same);
        EXPECT_GE(same, 0.999);
    }
}

TEST(Instances, AtAMillionthTheSceneRendersTheSameImage) {
    const Scene unit = stability_scene("case12_instances_unit.json");
    const Scene tiny = stability_scene("case12_instances_tiny.json");
    // The tiny scene's coordinates reach 4e-6 (the eye's z) = 0.52 2^-17.
    EXPECT_EQ(kernel::offset_shrink(flatten_scene(tiny, AccelPolicy{}).params), 17u);
    EXPECT_EQ(kernel::offset_shrink(flatten_scene(unit, AccelPolicy{}).params), 0u);
    for (bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "vulkan" : "cpu");
        const double same = same_8bit(render(unit, vulkan).image, render(tiny, vulkan).image, false);
        fmt::print("{}: same 8-bit pixels at 1e-6 as at 1 {:.4f}%\n", vulkan ? "vulkan" : "cpu", 100.0 * same);
        EXPECT_GE(same, 0.999);
    }
}

}  // namespace
}  // namespace vkrt
