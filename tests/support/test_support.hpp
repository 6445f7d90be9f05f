#pragma once
// Helpers shared by the tests: temporary files, the shipped scenes, the program,
// refusal messages, and renders on both backends.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/vulkan_backend.hpp"
#include "render/render.hpp"
#include "scene/scene.hpp"

namespace vkrt::test {

std::filesystem::path source_dir();

// A fresh directory under the system's temporary directory, unique to this process
// so that concurrent test runs do not share files.
std::filesystem::path temp_dir(const std::string& name);

// Every scene shipped under scenes/ (recursively): JSON and glTF files, sorted.
std::vector<std::filesystem::path> repo_scenes();

// A test name for a scene parameter (one of repo_scenes()): its stem, with every
// character gtest does not allow in a name replaced by '_'.
std::string scene_test_name(const ::testing::TestParamInfo<std::filesystem::path>& info);

// Checks a refusal's message as the loaders promise it: it starts with `prefix`,
// holds every piece, and is one line.
void expect_error_message(const std::string& message, const std::string& prefix,
                          std::initializer_list<std::string_view> pieces);

// Points the camera of a loaded glTF test file at the unit quad around the origin
// in the xy plane: from (0, 0, 3), a 30-degree view, size x size pixels, `spp`
// samples, the background `background`.
void view_quad_head_on(Scene& scene, std::uint32_t size, std::uint32_t spp, double background);

// Writes FILE, the buffer of that quad for a glTF test file: 4 positions (float3,
// bytes 0-47), 4 TEXCOORD_0 ((0, 0) at the top left, float2, bytes 48-79), then
// 6 unsigned-short indices (bytes 80-91).
void write_quad_buffer(const std::filesystem::path& file);
// The "buffers", "bufferViews" and "accessors" members of a glTF file that reads
// that buffer from `uri`: accessors 0 (POSITION), 1 (TEXCOORD_0) and 2 (indices).
std::string quad_buffer_json(const std::string& uri);

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

// The program exited 1 with exactly one "error: " line, holding every piece;
// returns that line (empty after a failure).
std::string expect_one_error(const ProgramRun& run, const std::vector<std::string>& pieces);

// A scene from JSON text, written to a temporary file `name`.json first (the loader
// reads files, and relative paths in the text are then relative to that directory).
Scene scene_from_text(const std::string& name, const std::string& text);

// The SceneError message that loading `file` gives; a test failure, and "", when it
// loads. scene_error_of does the same for a JSON scene written from `text`.
std::string load_error_of(const std::filesystem::path& file);
std::string scene_error_of(const std::string& name, const std::string& text);

// Writes `text` to `file` gzip-compressed, in one gzip member.
void write_gzip(const std::filesystem::path& file, const std::string& text);

// How many channel values of the image are NaN or infinite.
std::size_t nonfinite_values(const Image& image);

// What every render of the numerical-stability suite must be: no NaN or infinite
// pixel, no sample discarded as non-finite, none truncated by the loop budget.
void expect_sane(const RenderOutcome& out);

// The largest absolute difference between two images' channels (same size expected).
float max_abs_difference(const Image& a, const Image& b);

RenderOutcome render_cpu(const Scene& scene);
// Runs with the Khronos validation layer on; any validation message fails the test.
RenderOutcome render_vulkan(const Scene& scene);
// The same on the device and data paths `options` choose (validation forced on).
RenderOutcome render_vulkan_with(const Scene& scene, VulkanOptions options);

}  // namespace vkrt::test
