#include "test_support.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include <zlib.h>

#include "gpu/vulkan_backend.hpp"
#include "cpu/cpu_backend.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"

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
        if (entry.is_regular_file() && (ext == ".json" || ext == ".jsonc" || ext == ".glb" || ext == ".gltf")) {
            scenes.push_back(entry.path());
        }
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

std::string scene_test_name(const ::testing::TestParamInfo<std::filesystem::path>& info) {
    std::string name = info.param.stem().string();
    for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    return name;
}

void expect_error_message(const std::string& message, const std::string& prefix,
                          std::initializer_list<std::string_view> pieces) {
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
    for (std::string_view piece : pieces) {
        EXPECT_NE(message.find(piece), std::string::npos) << "missing '" << piece << "' in: " << message;
    }
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
}

std::string shell_quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

ProgramRun run_vkrt(const std::string& args, const std::filesystem::path& dir) {
    const auto err = dir / "stderr.txt";
    // A hang guard, not a speed limit: 300 s is far beyond any run here even on a
    // machine loaded by other work. -k: even a program that ignores SIGTERM goes away.
    const std::string command = "timeout -k 5 300 " + shell_quote(VKRT_EXE) + " " + args + " > " +
                                shell_quote((dir / "stdout.txt").string()) + " 2> " + shell_quote(err.string());
    const int status = std::system(command.c_str());
    std::ifstream in(err);
    ProgramRun run;
    run.stderr_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    EXPECT_NE(status, -1) << "could not run: " << command;
    EXPECT_TRUE(WIFEXITED(status)) << "shell ended by a signal; stderr:\n" << run.stderr_text;
    run.code = WEXITSTATUS(status);
    EXPECT_NE(run.code, 124) << "timed out (hang): " << command << "\nstderr:\n" << run.stderr_text;
    EXPECT_LT(run.code, 128) << "crashed (signal " << run.code - 128 << "): " << command << "\nstderr:\n"
                             << run.stderr_text;
    return run;
}

Scene load_at_size(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height) {
    Scene scene = load_scene(file);
    scene.camera.width = width;
    scene.camera.height = height;
    // As the command line does: a view framed to the model is framed for the new shape.
    if (scene.camera.framed) frame_scene(scene);
    return scene;
}

std::string expect_one_error(const ProgramRun& run, const std::vector<std::string>& pieces) {
    EXPECT_EQ(run.code, 1) << "stderr:\n" << run.stderr_text;
    std::vector<std::string> error_lines;
    std::istringstream lines(run.stderr_text);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("error: ", 0) == 0) error_lines.push_back(line);
    }
    if (error_lines.size() != 1u) {
        ADD_FAILURE() << "expected one error line; stderr:\n" << run.stderr_text;
        return {};
    }
    for (const std::string& piece : pieces) {
        EXPECT_NE(error_lines[0].find(piece), std::string::npos) << "missing '" << piece << "' in: " << error_lines[0];
    }
    return error_lines[0];
}

RenderOutcome render_cpu(const Scene& scene) {
    auto backend = make_cpu_backend();
    return render_scene(scene, *backend);
}

RenderOutcome render_vulkan(const Scene& scene) { return render_vulkan_with(scene, VulkanOptions{}); }

RenderOutcome render_vulkan_with(const Scene& scene, VulkanOptions options) {
    options.validation = true;
    auto backend = make_vulkan_backend(options);
    RenderOutcome out = render_scene(scene, *backend);
    // Every Vulkan render in the tests runs under the validation layer, and any
    // message it prints fails the test that rendered.
    EXPECT_EQ(out.stats.validation_messages, 0u) << "the validation layer reported problems (see stderr)";
    return out;
}

void write_gzip(const std::filesystem::path& file, const std::string& text) {
    gzFile out = gzopen(file.c_str(), "wb9");
    ASSERT_NE(out, nullptr) << file;
    const int written = text.empty() ? 0 : gzwrite(out, text.data(), static_cast<unsigned>(text.size()));
    ASSERT_EQ(gzclose(out), Z_OK) << file;
    ASSERT_EQ(written, static_cast<int>(text.size())) << file;
}

Scene scene_from_text(const std::string& name, const std::string& text) {
    const std::filesystem::path file = temp_dir("scene_text") / (name + ".json");
    std::ofstream(file) << text;
    return load_scene(file);
}

void write_quad_buffer(const std::filesystem::path& file) {
    const float positions[12] = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
    const float uvs[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const std::uint16_t indices[6] = {0, 2, 1, 0, 3, 2};
    std::ofstream bin(file, std::ios::binary);
    bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
    bin.write(reinterpret_cast<const char*>(uvs), sizeof uvs);
    bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
}

std::string quad_buffer_json(const std::string& uri) {
    return R"("buffers": [{"byteLength": 92, "uri": ")" + uri + R"("}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                      {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}])";
}

void view_quad_head_on(Scene& scene, std::uint32_t size, std::uint32_t spp, double background) {
    scene.camera.eye = glm::dvec3(0, 0, 3);
    scene.camera.look_at = glm::dvec3(0, 0, 0);
    scene.camera.up = glm::dvec3(0, 1, 0);
    scene.camera.fov = 30;
    scene.camera.width = scene.camera.height = size;
    scene.render.spp = spp;
    scene.render.background = glm::dvec3(background);
}

std::string load_error_of(const std::filesystem::path& file) {
    try {
        load_scene(file);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error loading " << file;
    return std::string();
}

std::string scene_error_of(const std::string& name, const std::string& text) {
    const std::filesystem::path file = temp_dir("scene_text") / (name + ".json");
    std::ofstream(file) << text;
    return load_error_of(file);
}

std::size_t nonfinite_values(const Image& image) {
    return static_cast<std::size_t>(
        std::count_if(image.rgb.begin(), image.rgb.end(), [](float v) { return !std::isfinite(v); }));
}

void expect_sane(const RenderOutcome& out) {
    EXPECT_EQ(nonfinite_values(out.image), 0u) << "NaN or infinite pixels";
    EXPECT_EQ(out.stats.nonfinite_samples, 0u) << "samples discarded as NaN or infinite";
    EXPECT_EQ(out.stats.truncated_samples, 0u) << "samples stopped by the loop budget";
}

float max_abs_difference(const Image& a, const Image& b) {
    EXPECT_EQ(a.rgb.size(), b.rgb.size());
    float worst = 0.0f;
    for (std::size_t i = 0; i < std::min(a.rgb.size(), b.rgb.size()); ++i) {
        worst = std::max(worst, std::abs(a.rgb[i] - b.rgb[i]));
    }
    return worst;
}

}  // namespace vkrt::test
