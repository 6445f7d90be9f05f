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

// A shell word holding s exactly.
std::string shell_quote(const std::string& s);

// The program (build/vkrt) run with `args`, words already quoted, with standard
// output to dir/stdout.txt and standard error captured. It runs under a timeout so
// that a hang fails the calling test instead of blocking the suite; a hang or crash
// is reported as a test failure here.
struct ProgramRun {
    int code = -1;  // exit status
    std::string stderr_text;
};
ProgramRun run_vkrt(const std::string& args, const std::filesystem::path& dir);

RenderOutcome render_cpu(const Scene& scene);
// Runs with the Khronos validation layer on; any validation message fails the test.
RenderOutcome render_vulkan(const Scene& scene);

}  // namespace vkrt::test
