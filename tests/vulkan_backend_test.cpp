// The Vulkan backend on a scene small enough to know every pixel: device listing and
// selection, exact background sums, counters, split invariance, the staging path,
// and silence from the validation layer throughout.
#include <algorithm>
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
    material.diffuse_kd = glm::vec4(0.8f, 0.2f, 0.2f, 1.0f);
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

// Every binding of render.comp is a storage texel buffer, and those count against the
// device's storage-image limits, whose guaranteed minimum (4) is below what the shader
// binds: a device short of them is passed over, and refused by name with the reason.
TEST(VulkanBackend, DeviceWithTooFewStorageTexelBuffersIsRefused) {
    gpu::PhysicalDevice enough;
    enough.info.index = 0;
    enough.info.name = "roomy";
    enough.has_compute = true;
    enough.api_version = VK_API_VERSION_1_1;
    enough.storage_texel_buffers = gpu::kBindingCount;
    gpu::PhysicalDevice short_of_them = enough;
    short_of_them.info.index = 1;
    short_of_them.info.name = "cramped";
    short_of_them.storage_texel_buffers = gpu::kBindingCount - 1;
    short_of_them.type = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;   // preferred, were it usable

    const std::vector<gpu::PhysicalDevice> both{enough, short_of_them};
    EXPECT_EQ(gpu::select_device(both, "").info.name, "roomy");
    const std::string needs = std::to_string(gpu::kBindingCount) + " storage texel buffers";
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

// The sums of `n` samples of radiance `v`, as the kernel adds them.
kernel::PixelSum repeated(glm::vec3 v, std::uint32_t n) {
    kernel::PixelSum s{};
    for (std::uint32_t i = 0; i < n; ++i) kernel::add_sample(s, v);
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
        EXPECT_GE(r.setup_seconds, 0.0);
        EXPECT_GT(r.render_seconds, 0.0);
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

// A grid array's view counts 4-byte texels: a buffer one texel past the device's
// maxTexelBufferElements is refused, naming the buffer and the limit, before any
// memory is allocated (counted in 16-byte texels it would have passed).
TEST(VulkanBuffer, TheTexelLimitCountsTheViewsTexels) {
    const gpu::VulkanContext context(VulkanOptions{"lavapipe", false});
    const std::uint64_t max = context.properties().limits.maxTexelBufferElements;
    try {
        const gpu::VulkanBuffer refs(context, "grid refs", (max + 1) * 4, gpu::kBindingUsage, gpu::Placement::Device, 4);
        FAIL() << "a buffer of " << max + 1 << " 4-byte texels was accepted";
    } catch (const GpuError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("grid refs"), std::string::npos) << message;
        EXPECT_NE(message.find("maxTexelBufferElements"), std::string::npos) << message;
        EXPECT_NE(message.find("4-byte texels"), std::string::npos) << message;
    }
    EXPECT_EQ(gpu::texel_bytes(gpu::index(gpu::Binding::grid_refs)), 4u);
    EXPECT_EQ(gpu::texel_bytes(gpu::index(gpu::Binding::spheres)), 16u);
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
    const RenderResult r = backend->render(tiny_scene(), SampleRange{0, samples},
                                           [&](std::uint32_t done, std::uint32_t total) {
                                               EXPECT_EQ(total, samples);
                                               reported.push_back(done);
                                           });
    ASSERT_GE(reported.size(), 2u) << "the first batch holds one sample";
    EXPECT_EQ(reported.front(), 1u);
    EXPECT_EQ(reported.back(), samples);
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
    for (std::size_t i = 0; i < r.sums.size(); ++i) {
        EXPECT_EQ(samples_summed(r.sums[i]), samples);
        EXPECT_EQ(r.counters[i].rays.x, samples);
    }
    EXPECT_EQ(backend->validation_messages(), 0u);
}

TEST(VulkanBackend, TallImagesAreDispatchedInBandsCoveringEveryRowOnce) {
    // 4 x 200 pixels: 25 workgroup rows, four bands of at most 8. Every pixel must
    // receive each sample exactly once, and progress moves band by band.
    FlatScene scene = tiny_scene();
    kernel::set_image_height(scene.params, 200);
    kernel::set_camera_down(scene.params, glm::vec3(0.0f, -2.0f / 200.0f, 0.0f));
    const std::unique_ptr<Backend> backend = lavapipe();
    const std::uint32_t samples = 3;
    std::vector<std::uint32_t> reported;
    const RenderResult r = backend->render(scene, SampleRange{0, samples}, [&](std::uint32_t done, std::uint32_t total) {
        EXPECT_EQ(total, samples * 4);
        reported.push_back(done);
    });
    ASSERT_EQ(r.sums.size(), 4u * 200u);
    for (std::size_t i = 0; i < r.sums.size(); ++i) {
        ASSERT_EQ(samples_summed(r.sums[i]), samples) << "pixel " << i;
        ASSERT_EQ(r.counters[i].rays.x, samples) << "pixel " << i;
    }
    ASSERT_FALSE(reported.empty());
    EXPECT_EQ(reported.front(), 1u) << "the first batch is one band";
    EXPECT_EQ(reported.back(), samples * 4);
    EXPECT_EQ(backend->validation_messages(), 0u);
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
    scene.materials[0].emission_fresnel = glm::vec4(1.0f, 0.5f, 0.125f, 0.0f);
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

// lavapipe has only mapped memory, so without this switch CI would never run the
// staging copies a discrete GPU takes.
TEST(VulkanBackend, StagingPathMatchesMappedPath) {
    const FlatScene scene = tiny_scene();
    const RenderResult mapped = lavapipe()->render(scene, SampleRange{0, 3});
    ASSERT_EQ(setenv("VKRT_VULKAN_FORCE_STAGING", "1", 1), 0);
    const std::unique_ptr<Backend> backend = lavapipe();
    unsetenv("VKRT_VULKAN_FORCE_STAGING");
    const RenderResult staged = backend->render(scene, SampleRange{0, 3});
    EXPECT_EQ(staged.sums, mapped.sums);
    EXPECT_EQ(staged.counters, mapped.counters);
    EXPECT_EQ(backend->validation_messages(), 0u);
}

// The renderer reads its params from a texel buffer, not a uniform buffer: lavapipe
// compiles a new shader variant for uniform-buffer values that decide branches, on
// every submission (render.comp says more). Checked on the SPIR-V itself, so a
// uniform block that creeps back fails here and not only as a slower benchmark.
TEST(VulkanBackend, ShaderDeclaresNoUniformBuffer) {
    constexpr std::uint32_t kOpVariable = 59;
    constexpr std::uint32_t kStorageUniform = 2;
    constexpr std::uint32_t kStorageUniformConstant = 0;  // texel buffers, sampled and storage
    const std::span<const std::uint32_t> words(render_comp_spv, std::size(render_comp_spv));
    ASSERT_GT(words.size(), 5u);
    ASSERT_EQ(words[0], 0x07230203u);  // the SPIR-V magic number
    int variables = 0;
    int texel_buffers = 0;
    for (std::size_t i = 5; i < words.size();) {
        const std::uint32_t count = words[i] >> 16;
        ASSERT_GT(count, 0u) << "malformed instruction at word " << i;
        if ((words[i] & 0xFFFFu) == kOpVariable) {
            ++variables;
            EXPECT_NE(words[i + 3], kStorageUniform) << "a uniform or storage block, result id " << words[i + 2];
            texel_buffers += words[i + 3] == kStorageUniformConstant ? 1 : 0;
        }
        i += count;
    }
    EXPECT_GT(variables, 0);
    EXPECT_EQ(texel_buffers, int(gpu::kBindingCount));  // every binding, the params among them
}

// The host folds the features into the SPIR-V before the driver sees it
// (gpu/spirv_specialize.hpp): lavapipe otherwise inlines the whole kernel, switched
// off or not, and took 2.1-2.3 s to create a pipeline. All features on, all off and
// the default scene's set must come out as valid modules with no specialization
// constant left; a refusal falls back to the slow path (with a warning).
TEST(VulkanBackend, FeaturesAreFoldedIntoTheSpirvOnTheHost) {
    constexpr std::uint32_t kOpSpecConstantTrue = 48, kOpSpecConstantFalse = 49, kOpSpecConstantOp = 52;
    const std::span<const std::uint32_t> words(render_comp_spv, std::size(render_comp_spv));
    auto spec_constants = [](std::span<const std::uint32_t> module) {
        int n = 0;
        for (std::size_t i = 5; i < module.size(); i += module[i] >> 16) {
            const std::uint32_t op = module[i] & 0xFFFFu;
            n += op == kOpSpecConstantTrue || op == kOpSpecConstantFalse || op == kOpSpecConstantOp ? 1 : 0;
        }
        return n;
    };
    ASSERT_GT(spec_constants(words), 0);
    // All on, all off, and the default scene's set (spheres, triangles, point lights,
    // shadows, specular, ambient).
    const std::vector<std::uint32_t> local = {
        std::uint32_t(Feature::HAS_SPHERES), std::uint32_t(Feature::HAS_TRIANGLES),
        std::uint32_t(Feature::HAS_POINT_LIGHTS), std::uint32_t(Feature::HAS_SHADOWS),
        std::uint32_t(Feature::HAS_SPECULAR), std::uint32_t(Feature::HAS_AMBIENT)};
    for (const int set : {0, 1, 2}) {
        std::unordered_map<std::uint32_t, bool> values;
        for (std::uint32_t id = 0; id < kFeatureCount; ++id) {
            values[id] = set == 0 || (set == 2 && std::find(local.begin(), local.end(), id) != local.end());
        }
        std::string error;
        const std::vector<std::uint32_t> out = gpu::specialize_spirv(words, values, error);
        SCOPED_TRACE("feature set " + std::to_string(set));
        ASSERT_FALSE(out.empty()) << error;
        EXPECT_TRUE(error.empty()) << error;
        EXPECT_EQ(spec_constants(out), 0);
        EXPECT_TRUE(spvtools::SpirvTools(SPV_ENV_VULKAN_1_1).Validate(out));
        if (set != 0) {
            EXPECT_LT(out.size(), words.size() / 2) << "the switched-off code was not removed";
        }
    }
}

}  // namespace
}  // namespace vkrt
