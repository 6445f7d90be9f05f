// How the Vulkan backend lays a scene out on a device, without a device: the one
// scene buffer (gpu/scene_pack.hpp), the data paths and slabs planned from a
// device's limits (gpu/data_paths.hpp), and the limit profiles
// (gpu/device_limits.hpp).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "gpu/data_paths.hpp"
#include "gpu/device_limits.hpp"
#include "gpu/scene_pack.hpp"
#include "gpu/vulkan_backend.hpp"

namespace vkrt {
namespace {

using gpu::DataPaths;
using gpu::DataSizes;
using gpu::DeviceLimits;
using gpu::PathChoice;

const DeviceLimits& minimum() { return gpu::find_profile("minimum").limits; }

// Texels per record, from the records themselves: the test follows the layout.
constexpr std::uint32_t kMaterial = sizeof(kernel::Material) / 16;
constexpr std::uint32_t kSphere = sizeof(kernel::Sphere) / 16;
constexpr std::uint32_t kTriangle = sizeof(kernel::Triangle) / 16;

FlatScene scene_with_arrays() {
    FlatScene scene;
    scene.materials.resize(2);
    scene.spheres.resize(3);
    scene.spheres[1].center_radius = glm::vec4(1.0f, 2.0f, 3.0f, 4.0f);
    scene.triangles.resize(1);
    scene.grid_nodes = {0, 2, 5};
    scene.grid_refs = {7, 8, 9, 10, 11};
    return scene;
}

TEST(ScenePack, ArraysFollowOneAnotherAndTheBasesSayWhere) {
    const FlatScene scene = scene_with_arrays();
    const gpu::ScenePack pack = gpu::pack_scene(scene, 16);
    const std::uint32_t spheres = 2 * kMaterial;
    const std::uint32_t triangles = spheres + 3 * kSphere;
    const std::uint32_t end = triangles + kTriangle;
    const std::uint32_t words = (end + 15) / 16 * 16;
    ASSERT_LT(end, words) << "the example needs padding before the words";
    // In the order of kernel/arrays.glsl's lines (materials, spheres, triangles, rings,
    // ...), each base found by its array's id.
    auto base = [&](ArrayId id) { return pack.bases[static_cast<std::uint32_t>(id)]; };
    EXPECT_EQ(base(ArrayId::materials), 0u);
    EXPECT_EQ(base(ArrayId::spheres), spheres);
    EXPECT_EQ(base(ArrayId::triangles), triangles);
    EXPECT_EQ(base(ArrayId::rings), end);       // empty arrays take no room
    EXPECT_EQ(base(ArrayId::emitters), end);
    // The uint arrays from the next multiple of 16 texels, counted in words.
    EXPECT_EQ(pack.words_start, words);
    EXPECT_EQ(pack.bases[gpu::kSceneArrays], words);
    EXPECT_EQ(base(ArrayId::grid_nodes), 0u);   // in words
    EXPECT_EQ(base(ArrayId::grid_refs), 3u);
    EXPECT_EQ(pack.word_count, 8u);
    EXPECT_EQ(pack.texel_count, words + 2);
    // The element is where its base says, bit for bit.
    std::vector<kernel::uvec4> texels(pack.texel_count, kernel::uvec4(7u));
    gpu::write_scene(scene, pack, texels.data());
    EXPECT_EQ(std::memcmp(&texels[spheres + kSphere], &scene.spheres[1], sizeof(kernel::Sphere)), 0);
    EXPECT_EQ(texels[words - 1], kernel::uvec4(0u)) << "the padding before the words is zero";
    const auto* word = reinterpret_cast<const std::uint32_t*>(&texels[words]);
    EXPECT_EQ(word[3 + 4], 11u);
}

TEST(ScenePack, WithoutUintArraysNothingIsPadded) {
    FlatScene scene = scene_with_arrays();
    scene.grid_nodes.clear();
    scene.grid_refs.clear();
    const gpu::ScenePack pack = gpu::pack_scene(scene, 16);
    const std::uint32_t end = 2 * kMaterial + 3 * kSphere + kTriangle;
    EXPECT_EQ(pack.words_start, end);
    EXPECT_EQ(pack.texel_count, end);
}

TEST(ScenePack, AnEmptySceneStillFillsOneTexel) {
    const gpu::ScenePack pack = gpu::pack_scene(FlatScene{}, 16);
    EXPECT_EQ(pack.texel_count, 1u);
    EXPECT_EQ(pack.word_count, 0u);
}

DataSizes sizes(std::uint64_t scene_texels, std::uint32_t width, std::uint32_t height) {
    return {scene_texels, scene_texels, 0, width, height};
}

TEST(DataPaths, TexelBuffersWhileTheyHoldSceneAndImage) {
    const DataPaths p = gpu::plan_data_paths(minimum(), true, sizes(1000, 64, 48));
    EXPECT_FALSE(p.scene_in_storage);
    EXPECT_FALSE(p.params_in_uniform);   // a CPU device: decision 0001
    EXPECT_EQ(p.slab_rows, 48u);         // 64 x 48 x 10 texels fit 65,536
}

TEST(DataPaths, ParamsFromAUniformBufferOnGpus) {
    EXPECT_TRUE(gpu::plan_data_paths(minimum(), false, sizes(1000, 64, 48)).params_in_uniform);
    EXPECT_FALSE(gpu::plan_data_paths(minimum(), false, sizes(1000, 64, 48), PathChoice::Automatic,
                                      PathChoice::Texel).params_in_uniform);
}

TEST(DataPaths, LargeImagesAreRenderedInSlabsOfEightRows) {
    // 65,536 texels hold 12.8 rows of 512 pixels of 10 texels: slabs of 8.
    const DataPaths p = gpu::plan_data_paths(minimum(), true, sizes(1000, 512, 512));
    EXPECT_FALSE(p.scene_in_storage);
    EXPECT_EQ(p.slab_rows, 8u);
}

TEST(DataPaths, ASceneTooLargeForTexelBuffersGoesToStorageBuffers) {
    const DataPaths p = gpu::plan_data_paths(minimum(), true, sizes(70000, 512, 512));
    EXPECT_TRUE(p.scene_in_storage);
    // 2^27 bytes hold 1,638 rows of 512 pixels of 160 bytes: the whole image.
    EXPECT_EQ(p.slab_rows, 512u);
}

TEST(DataPaths, ImagesTooWideForTexelBuffersGoToStorageBuffers) {
    // Eight rows of 1,200 pixels need 96,000 texels.
    EXPECT_TRUE(gpu::plan_data_paths(minimum(), true, sizes(100, 1200, 100)).scene_in_storage);
}

TEST(DataPaths, WhatFitsNowhereIsRefusedNamingTheLimits) {
    try {
        gpu::plan_data_paths(minimum(), true, sizes(std::uint64_t(1) << 24, 64, 48));
        FAIL() << "a 256 MiB scene was planned on a device of 128 MiB buffers";
    } catch (const gpu::SceneDoesNotFit& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("maxTexelBufferElements is 65536"), std::string::npos) << message;
        EXPECT_NE(message.find("maxStorageBufferRange 134217728"), std::string::npos) << message;
    }
    // A forced path that cannot hold the scene is refused too.
    EXPECT_THROW(gpu::plan_data_paths(minimum(), true, sizes(70000, 64, 48), PathChoice::Texel), gpu::SceneDoesNotFit);
    EXPECT_THROW(gpu::plan_data_paths(minimum(), true, sizes(100, 64, 48), PathChoice::Address), gpu::SceneDoesNotFit);
}

// Why plan_data_paths refused; empty when it did not.
std::string refusal(const DeviceLimits& limits, const DataSizes& s) {
    try {
        gpu::plan_data_paths(limits, false, s);
    } catch (const gpu::SceneDoesNotFit& e) {
        return e.what();
    }
    return "";
}

// The minimum's bindings (128 MiB at most), with buffer device addresses.
DeviceLimits addressing() {
    DeviceLimits l = minimum();
    l.buffer_device_address = true;
    return l;
}

TEST(DataPaths, ASceneTooLargeForAnyBindingIsReadByAddress) {
    const std::uint64_t texels = (std::uint64_t(1) << 27) / 16 + 1;  // one texel past 128 MiB
    const DataPaths p = gpu::plan_data_paths(addressing(), false, sizes(texels, 512, 512));
    EXPECT_TRUE(p.scene_by_address);
    EXPECT_TRUE(p.scene_in_storage);  // the pixels
    EXPECT_EQ(p.slab_rows, 512u);
    // Below the storage range, the bindings are kept.
    EXPECT_FALSE(gpu::plan_data_paths(addressing(), false, sizes(texels - 1, 512, 512)).scene_by_address);
}

TEST(DataPaths, ByAddressTheSceneIsCappedByOneAllocation) {
    DeviceLimits l = addressing();
    l.allocation_bytes = std::uint64_t(1) << 28;
    EXPECT_TRUE(gpu::plan_data_paths(l, false, sizes(l.allocation_bytes / 16, 64, 48)).scene_by_address);
    const std::string too_large = refusal(l, sizes(l.allocation_bytes / 16 + 1, 64, 48));
    EXPECT_NE(too_large.find("maxMemoryAllocationSize 268435456"), std::string::npos) << too_large;
    const std::string no_address = refusal(minimum(), sizes(std::uint64_t(1) << 24, 64, 48));
    EXPECT_NE(no_address.find("lacks bufferDeviceAddress"), std::string::npos) << no_address;
}

TEST(DeviceLimits, TheMinimumProfileCanRunTheRenderer) {
    EXPECT_EQ(gpu::missing(minimum()), "");
    for (const gpu::DeviceProfile& p : gpu::device_profiles()) {
        EXPECT_EQ(gpu::missing(p.limits), "") << p.name;
        EXPECT_FALSE(p.description.empty()) << p.name;
    }
}

TEST(DeviceLimits, ClampingTakesTheWorseOfEachLimit) {
    DeviceLimits big = minimum();
    big.texel_elements = 1u << 27;
    big.texel_offset_alignment = 16;
    big.allocation_bytes = std::uint64_t(1) << 34;
    big.mapped_device_memory = true;
    big.timestamps = true;
    big.buffer_device_address = true;
    const DeviceLimits c = gpu::clamp_to(big, minimum());
    EXPECT_EQ(c.texel_elements, 65536u);
    EXPECT_EQ(c.texel_offset_alignment, 256u);
    EXPECT_EQ(c.allocation_bytes, std::uint64_t(1) << 30);
    EXPECT_FALSE(c.mapped_device_memory);
    EXPECT_FALSE(c.timestamps);
    EXPECT_FALSE(c.buffer_device_address);
}

TEST(DeviceLimits, WhatIsMissingIsNamed) {
    DeviceLimits l = minimum();
    l.storage_buffers = 1;
    l.push_constant_bytes = 32;
    const std::string m = gpu::missing(l);
    EXPECT_NE(m.find("2 storage buffers"), std::string::npos) << m;
    EXPECT_NE(m.find("96 bytes of push constants"), std::string::npos) << m;
}

TEST(DeviceLimits, AnUnknownProfileListsTheKnownOnes) {
    try {
        gpu::find_profile("nonesuch");
        FAIL();
    } catch (const GpuError& e) {
        EXPECT_NE(std::string(e.what()).find("minimum"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace vkrt
