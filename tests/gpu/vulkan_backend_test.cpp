// The Vulkan backend on a scene small enough to know every pixel: device listing and
// selection, exact background sums, counters, split invariance, the staging path,
// and silence from the validation layer throughout.
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cpu/cpu_backend.hpp"
#include "gpu/vulkan_backend.hpp"
#include "gpu/device_limits.hpp"
#include "gpu/vulkan_buffer.hpp"
#include "gpu/vulkan_context.hpp"
#include "gpu/vulkan_pipeline.hpp"
#include "render/pixel_sums.hpp"
#include "render_comp_spv.h"
#include "gpu/spirv_specialize.hpp"
#include "flatten/features.hpp"

#include <spirv-tools/libspirv.hpp>

namespace vkrt {
namespace {

constexpr std::uint32_t kSize = 4;
const glm::vec4 kBackground(0.25f, 0.5f, 0.75f, 0.0f);

// A 4x4 image with a 90 degree field of view looking down -z at a sphere of radius
// 1.5 three units away: the sphere covers exactly the central 2x2 pixels (their
// centres are 19.5 degrees off axis, the sphere's rim 30, the next pixels 38 or more).
FlatScene tiny_scene() {
    FlatScene scene;
    kernel::Params& p = scene.params;
    kernel::set_camera_eye(p, glm::vec3(0.0f));
    kernel::set_camera_corner(p, glm::vec3(-1.0f, 1.0f, -1.0f));
    kernel::set_camera_right(p, glm::vec3(2.0f / kSize, 0.0f, 0.0f));
    kernel::set_camera_down(p, glm::vec3(0.0f, -2.0f / kSize, 0.0f));
    kernel::set_ambient_light(p, glm::vec3(0.0f));
    kernel::set_background(p, glm::vec3(kBackground));
    kernel::set_image_width(p, kSize);
    kernel::set_image_height(p, kSize);
    kernel::set_aa_per_side(p, 1);
    kernel::set_sphere_count(p, 1);
    kernel::set_material_count(p, 1);
    kernel::set_loop_budget(p, kernel::DEFAULT_LOOP_BUDGET);
    kernel::set_max_depth(p, 5);
    scene.features.set(Feature::HAS_SPHERES, true);
    kernel::Material material{};
    material.diffuse = glm::vec3(0.8f, 0.2f, 0.2f);
    material.kd = 1.0f;
    scene.materials.push_back(material);
    scene.spheres.push_back(kernel::Sphere{glm::vec4(0.0f, 0.0f, -3.0f, 1.5f), glm::uvec4(0)});
    scene.samples_per_pixel = 1;
    return scene;
}

bool on_sphere(std::uint32_t x, std::uint32_t y) {
    return (x == 1 || x == 2) && (y == 1 || y == 2);
}

std::unique_ptr<Backend> lavapipe() {
    return make_vulkan_backend(VulkanOptions{"lavapipe", true});
}

TEST(VulkanBackend, ListsDevicesIncludingLavapipe) {
    const std::vector<DeviceInfo> devices = list_vulkan_devices();
    ASSERT_FALSE(devices.empty());
    for (std::uint32_t i = 0; i < devices.size(); ++i) {
        EXPECT_EQ(devices[i].index, i);
        EXPECT_FALSE(devices[i].name.empty());
        EXPECT_FALSE(devices[i].api_version.empty());
    }
    const std::unique_ptr<Backend> backend = lavapipe();
    EXPECT_EQ(backend->name(), "vulkan");
    EXPECT_NE(backend->device_name().find("llvmpipe"), std::string::npos) << backend->device_name();
    EXPECT_EQ(backend->validation_messages(), 0u);
}

TEST(VulkanBackend, SelectsByIndex) {
    const std::unique_ptr<Backend> backend = make_vulkan_backend(VulkanOptions{"0", true});
    EXPECT_EQ(backend->device_name(), list_vulkan_devices().at(0).name);
}

TEST(VulkanBackend, UnknownDeviceListsTheAvailableOnes) {
    try {
        make_vulkan_backend(VulkanOptions{"nonexistent-device", false});
        FAIL() << "expected GpuError";
    } catch (const GpuError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("available"), std::string::npos) << message;
        EXPECT_NE(message.find("nonexistent-device"), std::string::npos) << message;
        EXPECT_NE(message.find(list_vulkan_devices().at(0).name), std::string::npos) << message;
    }
    EXPECT_THROW(make_vulkan_backend(VulkanOptions{"99", false}), GpuError);
}

// A device as enumerated, for selection alone: Vulkan 1.1, compute, the
// specification's minimum limits.
gpu::PhysicalDevice fake_device(std::uint32_t index, const char* name, VkPhysicalDeviceType type) {
    gpu::PhysicalDevice d;
    d.info.index = index;
    d.info.name = name;
    d.type = type;
    d.has_compute = true;
    d.api_version = VK_API_VERSION_1_1;
    d.limits = gpu::find_profile("minimum").limits;
    return d;
}

// A device short of any limit the renderer relies on (gpu/device_limits.hpp) is
// passed over, and refused by name with the reason. The descriptor set needs 4
// storage texel buffers, the specification's guaranteed minimum.
TEST(VulkanBackend, DeviceShortOfALimitIsRefused) {
    const gpu::PhysicalDevice enough = fake_device(0, "roomy", VK_PHYSICAL_DEVICE_TYPE_OTHER);
    // Preferred, were it usable.
    gpu::PhysicalDevice short_of_them = fake_device(1, "cramped", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
    short_of_them.limits.storage_images = 3;

    const std::vector<gpu::PhysicalDevice> both{enough, short_of_them};
    EXPECT_EQ(gpu::select_device(both, "").info.name, "roomy");
    const std::string needs = "4 storage texel buffers";
    try {
        gpu::select_device(both, "cramped");
        FAIL() << "expected GpuError";
    } catch (const GpuError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("cramped"), std::string::npos) << message;
        EXPECT_NE(message.find(needs), std::string::npos) << message;
    }
    try {
        gpu::select_device({short_of_them}, "");
        FAIL() << "expected GpuError";
    } catch (const GpuError& e) {
        EXPECT_NE(std::string(e.what()).find(needs), std::string::npos) << e.what();
    }
}

// When the device selection would pick cannot hold a scene, the backend moves to the
// preferred one of those that can (unless the user named a device).
TEST(VulkanBackend, TheDeviceThatHoldsTheSceneIsPreferred) {
    const gpu::PhysicalDevice small = fake_device(0, "small", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
    gpu::PhysicalDevice large = fake_device(1, "large", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU);
    large.limits.texel_elements = 1u << 27;
    const std::vector<gpu::PhysicalDevice> both{small, large};
    auto scene_of = [](std::uint64_t texels) { return gpu::DataSizes{texels, texels, 0, 512, 512}; };
    EXPECT_EQ(gpu::device_for_scene(both, scene_of(1000))->info.name, "small");   // discrete first
    EXPECT_EQ(gpu::device_for_scene(both, scene_of(1u << 24))->info.name, "large");  // 256 MiB
    EXPECT_EQ(gpu::device_for_scene(both, scene_of(1u << 28)), nullptr);
}

// The sums of `n` samples of radiance `v`, as the kernel adds them.
kernel::PixelSum repeated(glm::vec3 v, std::uint32_t n) {
    kernel::PixelSum s{};
    for (std::uint32_t i = 0; i < n; ++i) kernel::add_sample(s, v, false);
    return s;
}

TEST(VulkanBackend, TinyRenderHasExactSums) {
    testing::internal::CaptureStderr();
    {
        const std::unique_ptr<Backend> backend = lavapipe();
        const FlatScene scene = tiny_scene();
        const std::uint32_t samples = 2;
        const RenderResult r = backend->render(scene, SampleRange{0, samples});
        ASSERT_EQ(r.width, kSize);
        ASSERT_EQ(r.height, kSize);
        ASSERT_EQ(r.sums.size(), kSize * kSize);
        ASSERT_EQ(r.counters.size(), kSize * kSize);
        for (std::uint32_t y = 0; y < kSize; ++y) {
            for (std::uint32_t x = 0; x < kSize; ++x) {
                const glm::uvec4 c = r.counters[y * kSize + x].rays;
                SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
                // No lights, no ambient, no emission: the sphere is black.
                const glm::vec3 expected = on_sphere(x, y) ? glm::vec3(0.0f) : glm::vec3(kBackground);
                EXPECT_EQ(r.sums[y * kSize + x], repeated(expected, samples));
                EXPECT_EQ(c, glm::uvec4(samples, 0, 0, 0));
            }
        }
        // Both phases were timed: the pipeline and uploads, then the sample loop.
        EXPECT_GT(r.setup_seconds, 0.0);
        EXPECT_TRUE(std::isfinite(r.setup_seconds)) << r.setup_seconds;
        EXPECT_GT(r.render_seconds, 0.0);
        EXPECT_TRUE(std::isfinite(r.render_seconds)) << r.render_seconds;
        EXPECT_EQ(backend->validation_messages(), 0u);
    }
    // Teardown is checked too: the messages print even when the counter is gone.
    const std::string log = testing::internal::GetCapturedStderr();
    EXPECT_EQ(log.find("vulkan validation:"), std::string::npos) << log;
}

// A NaN or infinite sample is counted, never added to the sums, on both backends:
// the check reads the float's bits (ray.glsl, is_finite_bits), which no compiler may
// fold away. Here the background is NaN, then infinite, so every ray that misses
// the sphere brings back a non-finite sample.
TEST(VulkanBackend, NonFiniteSamplesAreCountedNotSummed) {
    const std::uint32_t samples = 2;
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        FlatScene scene = tiny_scene();
        kernel::set_background(scene.params, glm::vec3(0.1f, bad, 0.1f));
        for (const std::unique_ptr<Backend>& backend : {lavapipe(), make_cpu_backend(1)}) {
            const RenderResult r = backend->render(scene, SampleRange{0, samples});
            for (std::uint32_t i = 0; i < kSize * kSize; ++i) {
                SCOPED_TRACE(backend->name() + " pixel " + std::to_string(i) + " background " + std::to_string(bad));
                const bool sphere = on_sphere(i % kSize, i / kSize);
                EXPECT_EQ(r.counters[i].work[kernel::WORK_NONFINITE], sphere ? 0u : samples);
                EXPECT_EQ(r.sums[i], repeated(glm::vec3(0.0f), sphere ? samples : 0u));
            }
        }
    }
}

TEST(VulkanBackend, SplitRangesGiveTheSameSums) {
    const std::unique_ptr<Backend> backend = lavapipe();
    FlatScene scene = tiny_scene();
    scene.features.set(Feature::HAS_JITTER, true);  // make the samples differ
    kernel::set_sample_seed(scene.params, 7);
    const RenderResult whole = backend->render(scene, SampleRange{0, 2});
    const RenderResult first = backend->render(scene, SampleRange{0, 1});
    const RenderResult second = backend->render(scene, SampleRange{1, 1});
    bool any_partial = false;
    for (std::size_t i = 0; i < whole.sums.size(); ++i) {
        EXPECT_EQ(whole.sums[i], kernel::add_sums(first.sums[i], second.sums[i])) << "pixel " << i;
        EXPECT_EQ(whole.counters[i], first.counters[i] + second.counters[i]) << "pixel " << i;
        // With jitter the rim pixels see the sphere in some samples only.
        any_partial = any_partial || (first.sums[i] != second.sums[i]);
    }
    EXPECT_TRUE(any_partial) << "the two samples should differ somewhere";
    EXPECT_EQ(backend->validation_messages(), 0u);
}

TEST(VulkanBackend, ManySamplesSpanSeveralBatches) {
    const std::unique_ptr<Backend> backend = lavapipe();
    const std::uint32_t samples = 40;
    std::vector<std::uint32_t> reported;
    std::uint32_t last_total = 0;
    const RenderResult r = backend->render(tiny_scene(), SampleRange{0, samples},
                                           [&](std::uint32_t done, std::uint32_t total) {
                                               reported.push_back(done);
                                               last_total = total;
                                           });
    ASSERT_GE(reported.size(), 2u) << "the first batch holds one sample";
    EXPECT_NEAR(reported.front(), last_total / samples, 1.0);
    EXPECT_EQ(reported.back(), last_total);
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
    for (std::size_t i = 0; i < r.sums.size(); ++i) {
        EXPECT_EQ(samples_summed(r.sums[i]), samples);
        EXPECT_EQ(r.counters[i].rays.x, samples);
    }
    EXPECT_EQ(backend->validation_messages(), 0u);
}

TEST(VulkanBackend, TilesCoverEveryPixelOnce) {
    // Tiles as small as they go (a bound no tile can meet), split after the first
    // tile of the first sample: at 20 x 200 the rest of that sample is the rows below
    // it, at 600 x 40 the rest of its row of tiles. 8 x 8 tiles then, the last ones
    // cut by the edges. Every pixel must receive each sample exactly once.
    for (const auto& [width, height] : {std::pair{20u, 200u}, std::pair{600u, 40u}}) {
        SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
        FlatScene scene = tiny_scene();
        kernel::set_image_width(scene.params, width);
        kernel::set_image_height(scene.params, height);
        kernel::set_camera_right(scene.params, glm::vec3(2.0f / float(width), 0.0f, 0.0f));
        kernel::set_camera_down(scene.params, glm::vec3(0.0f, -2.0f / float(height), 0.0f));
        VulkanOptions options{"lavapipe", true};
        options.submit_bound_seconds = 1e-9;
        const std::unique_ptr<Backend> backend = make_vulkan_backend(options);
        const std::uint32_t samples = 3;
        const RenderResult r = backend->render(scene, SampleRange{0, samples});
        ASSERT_EQ(r.sums.size(), std::size_t(width) * height);
        for (std::size_t i = 0; i < r.sums.size(); ++i) {
            ASSERT_EQ(samples_summed(r.sums[i]), samples) << "pixel " << i;
            ASSERT_EQ(r.counters[i].rays.x, samples) << "pixel " << i;
        }
        EXPECT_EQ(r.tile_width, 8u);
        EXPECT_EQ(r.tile_height, 8u);
        const RenderResult whole = lavapipe()->render(scene, SampleRange{0, samples});
        EXPECT_EQ(r.sums, whole.sums);
        EXPECT_EQ(r.counters, whole.counters);
        EXPECT_EQ(backend->validation_messages(), 0u);
    }
}

// A triangle far larger than the view, facing the camera, that glows: with the
// triangle feature on every pixel sees its emission; with it off, the very same
// buffers and counts (counts.y = 1, the triangle uploaded) must give pure
// background, because the specialization constant leaves the triangle loop out of
// the pipeline rather than the host leaving the data out.
FlatScene glowing_triangle_scene(bool has_triangles) {
    FlatScene scene = tiny_scene();
    scene.spheres.clear();
    scene.features.set(Feature::HAS_SPHERES, false);
    scene.features.set(Feature::HAS_TRIANGLES, has_triangles);
    scene.features.set(Feature::HAS_EMISSION, true);
    kernel::set_sphere_count(scene.params, 0);
    kernel::set_triangle_count(scene.params, 1);
    kernel::set_material_count(scene.params, 1);
    scene.materials[0].emission = glm::vec3(1.0f, 0.5f, 0.125f);
    // At z = -2 the view spans [-2, 2] in x and y; the front face, cross(p1 - p0,
    // p2 - p0) = +z, looks at the camera.
    kernel::Triangle tri{};
    tri.p0 = glm::vec4(-10.0f, -10.0f, -2.0f, 0.0f);
    tri.p1 = glm::vec4(30.0f, -10.0f, -2.0f, 0.0f);
    tri.p2 = glm::vec4(-10.0f, 30.0f, -2.0f, 0.0f);
    tri.meta = glm::uvec4(0);
    scene.triangles.push_back(tri);
    return scene;
}

TEST(VulkanBackend, SpecializationConstantsCompileTrianglesOut) {
    testing::internal::CaptureStderr();
    {
        const std::unique_ptr<Backend> backend = lavapipe();
        const std::uint32_t samples = 2;
        const RenderResult with = backend->render(glowing_triangle_scene(true), SampleRange{0, samples});
        const RenderResult without = backend->render(glowing_triangle_scene(false), SampleRange{0, samples});
        ASSERT_EQ(with.sums.size(), kSize * kSize);
        ASSERT_EQ(without.sums.size(), kSize * kSize);
        const glm::vec3 emission(1.0f, 0.5f, 0.125f);
        for (std::size_t i = 0; i < with.sums.size(); ++i) {
            SCOPED_TRACE("pixel " + std::to_string(i));
            EXPECT_EQ(with.sums[i], repeated(emission, samples));
            EXPECT_EQ(without.sums[i], repeated(glm::vec3(kBackground), samples));
            EXPECT_EQ(with.counters[i].rays, glm::uvec4(samples, 0, 0, 0));
            EXPECT_EQ(without.counters[i].rays, glm::uvec4(samples, 0, 0, 0));
        }
        EXPECT_EQ(backend->validation_messages(), 0u);
    }
    const std::string log = testing::internal::GetCapturedStderr();
    EXPECT_EQ(log.find("vulkan validation:"), std::string::npos) << log;
}

// Three samples of `scene` on lavapipe as `options` plan them give `reference`'s sums,
// silently.
void expect_same_sums(const FlatScene& scene, VulkanOptions options, const RenderResult& reference) {
    options.device = "lavapipe";
    options.validation = true;
    const std::unique_ptr<Backend> backend = make_vulkan_backend(options);
    const RenderResult r = backend->render(scene, SampleRange{0, 3});
    SCOPED_TRACE(r.data_paths);
    EXPECT_EQ(r.sums, reference.sums);
    EXPECT_EQ(r.counters, reference.counters);
    EXPECT_EQ(backend->validation_messages(), 0u);
}

// lavapipe has only mapped memory; the "minimum" profile has none, so the uploads
// go through staging buffers and the sums through a read-back copy, as on a
// discrete GPU.
TEST(VulkanBackend, StagingPathMatchesMappedPath) {
    const FlatScene scene = tiny_scene();
    VulkanOptions minimum;
    minimum.profile = "minimum";
    expect_same_sums(scene, minimum, lavapipe()->render(scene, SampleRange{0, 3}));
}

// Each data path of render_bindings.glsl, forced on lavapipe: the same sums.
TEST(VulkanBackend, EveryDataPathGivesTheSameSums) {
    const FlatScene scene = tiny_scene();
    const RenderResult reference = lavapipe()->render(scene, SampleRange{0, 3});
    using gpu::PathChoice;
    for (const PathChoice data : {PathChoice::Texel, PathChoice::Buffer, PathChoice::Address}) {
        for (const PathChoice params : {PathChoice::Texel, PathChoice::Buffer}) {
            VulkanOptions options;
            options.scene_path = data;
            options.params_path = params;
            expect_same_sums(scene, options, reference);
        }
    }
}

// A lost device (VK_ERROR_DEVICE_LOST, here injected) is replaced and the pass
// rendered again: the same sums, one reset reported.
TEST(VulkanBackend, LostDeviceIsReplacedAndThePassRenderedAgain) {
    const FlatScene scene = tiny_scene();
    const RenderResult reference = lavapipe()->render(scene, SampleRange{0, 5});
    VulkanOptions options{"lavapipe", true};
    options.lose_device_at_submission = 2;   // the first of the pass: 1 made the session
    const std::unique_ptr<Backend> backend = make_vulkan_backend(options);
    const std::unique_ptr<RenderSession> session = backend->begin(scene);
    testing::internal::CaptureStderr();
    const RenderResult r = session->render(SampleRange{0, 5});
    const std::string log = testing::internal::GetCapturedStderr();
    EXPECT_EQ(r.device_resets, 1u);
    EXPECT_NE(log.find("VK_ERROR_DEVICE_LOST"), std::string::npos) << log;
    EXPECT_NE(log.find("again on a new device"), std::string::npos) << log;
    EXPECT_EQ(r.sums, reference.sums);
    EXPECT_EQ(r.counters, reference.counters);
    // The session goes on, on its new device.
    EXPECT_EQ(session->render(SampleRange{0, 5}).sums, reference.sums);
    EXPECT_EQ(backend->validation_messages(), 0u);
}

// The host folds the features into the SPIR-V before the driver sees it
// (gpu/spirv_specialize.hpp): lavapipe otherwise inlines the whole kernel, switched
// off or not, and took 2.1-2.3 s to create a pipeline. All features on, all off and
// the default scene's set must come out as valid modules with no specialization
// constant left, and with most calls inlined (decision 0025: lavapipe creates the
// pipeline in half the time); a refusal falls back to the slow path (with a warning).
TEST(VulkanBackend, FeaturesAreFoldedIntoTheSpirvOnTheHost) {
    constexpr std::uint32_t kOpSpecConstantTrue = 48, kOpSpecConstantFalse = 49, kOpSpecConstantOp = 52;
    const std::span<const std::uint32_t> words(render_comp_spv, std::size(render_comp_spv));
    auto count_ops = [](std::span<const std::uint32_t> module, std::initializer_list<std::uint32_t> ops) {
        int n = 0;
        for (std::size_t i = 5; i < module.size(); i += module[i] >> 16) {
            n += std::find(ops.begin(), ops.end(), module[i] & 0xFFFFu) != ops.end() ? 1 : 0;
        }
        return n;
    };
    auto spec_constants = [&](std::span<const std::uint32_t> module) {
        return count_ops(module, {kOpSpecConstantTrue, kOpSpecConstantFalse, kOpSpecConstantOp});
    };
    constexpr std::uint32_t kOpFunctionCall = 57;
    const int calls_before = count_ops(words, {kOpFunctionCall});
    ASSERT_GT(calls_before, 100);
    ASSERT_GT(spec_constants(words), 0);
    // All on, all off, and the default scene's set (spheres, triangles, point lights,
    // shadows, specular, ambient), with the device choices.
    const std::vector<std::uint32_t> local = {
        std::uint32_t(Feature::HAS_SPHERES), std::uint32_t(Feature::HAS_TRIANGLES),
        std::uint32_t(Feature::HAS_POINT_LIGHTS), std::uint32_t(Feature::HAS_SHADOWS),
        std::uint32_t(Feature::HAS_SPECULAR), std::uint32_t(Feature::HAS_AMBIENT)};
    std::size_t all_on = 0;
    for (const int set : {0, 1, 2}) {
        std::unordered_map<std::uint32_t, bool> values;
        for (std::uint32_t id = 0; id < kFeatureCount; ++id) {
            values[id] = set == 0 || (set == 2 && std::find(local.begin(), local.end(), id) != local.end());
        }
#define DEVICE_CHOICE(id, name) values[id] = set == 1;
#include "render_bindings.glsl"
        std::string error;
        const std::vector<std::uint32_t> out = gpu::specialize_spirv(words, values, error);
        SCOPED_TRACE("feature set " + std::to_string(set));
        ASSERT_FALSE(out.empty()) << error;
        EXPECT_TRUE(error.empty()) << error;
        EXPECT_EQ(spec_constants(out), 0);
        EXPECT_TRUE(spvtools::SpirvTools(SPV_ENV_VULKAN_1_1).Validate(out));
        // Against all on, folded and inlined the same way (set 0 comes first).
        if (set == 0) all_on = out.size();
        if (set != 0) {
            EXPECT_LT(out.size(), all_on / 2) << "the switched-off code was not removed";
        }
        // All on keeps nearly every function; inlined, few calls remain (those with
        // an early return).
        EXPECT_LT(count_ops(out, {kOpFunctionCall}) * 4, calls_before) << "the calls were not inlined";
    }
}

}  // namespace
}  // namespace vkrt
