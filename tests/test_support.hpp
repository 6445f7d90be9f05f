#pragma once
// Helpers shared by the tests that render whole scenes on both backends.
#include <filesystem>
#include <string>
#include <vector>

#include "render/render.hpp"
#include "scene/scene.hpp"

namespace vkrt::test {

std::filesystem::path source_dir();

// A fresh directory under the system's temporary directory, unique to this process
// so that concurrent test runs do not share files.
std::filesystem::path temp_dir(const std::string& name);

// Every scene shipped under scenes/ (recursively), sorted.
std::vector<std::filesystem::path> repo_scenes();

// A scene file with its image size replaced, for fast renders.
Scene load_at_size(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height);

RenderOutcome render_cpu(const Scene& scene);
// Runs with the Khronos validation layer on; any validation message fails the test.
RenderOutcome render_vulkan(const Scene& scene);

}  // namespace vkrt::test
