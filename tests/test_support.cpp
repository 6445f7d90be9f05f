#include "test_support.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>

#include "gpu/vulkan_backend.hpp"
#include "ref/ref_backend.hpp"
#include "scene/load_scene.hpp"

namespace vkrt::test {

std::filesystem::path source_dir() { return VKRT_SOURCE_DIR; }

std::filesystem::path temp_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("vkrt_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::vector<std::filesystem::path> repo_scenes() {
    std::vector<std::filesystem::path> scenes;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(source_dir() / "scenes")) {
        const auto ext = entry.path().extension();
        if (entry.is_regular_file() && (ext == ".json" || ext == ".jsonc")) scenes.push_back(entry.path());
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

Scene load_at_size(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height) {
    Scene scene = load_scene(file);
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

RenderOutcome render_cpu(const Scene& scene) {
    auto backend = make_reference_backend();
    return render_scene(scene, *backend);
}

RenderOutcome render_vulkan(const Scene& scene) {
    auto backend = make_vulkan_backend(VulkanOptions{"", true});
    RenderOutcome out = render_scene(scene, *backend);
    // Every Vulkan render in the tests runs under the validation layer, and any
    // message it prints fails the test that rendered.
    EXPECT_EQ(out.stats.validation_messages, 0u) << "the validation layer reported problems (see stderr)";
    return out;
}

}  // namespace vkrt::test
