// The command line's options that the bad-input tests do not reach: what a user
// gets when everything is right.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "image/compare.hpp"
#include "image/image.hpp"
#include "test_support.hpp"
#include "vkrt_version.h"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

std::string read_file(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path scene(const std::string& name) { return test::source_dir() / "scenes" / (name + ".json"); }

TEST(Cli, VersionAndHelp) {
    const fs::path dir = test::temp_dir("cli_version");
    EXPECT_EQ(test::run_vkrt("--version", dir).code, 0);
    EXPECT_EQ(read_file(dir / "stdout.txt"), "vkrt " VKRT_VERSION " (kernel " VKRT_KERNEL_HASH ")\n");
    EXPECT_EQ(test::run_vkrt("render --help", dir).code, 0);
    const std::string help = read_file(dir / "stdout.txt");
    for (const char* option : {"--output", "--backend", "--device", "--width", "--height", "--spp", "--time", "--samples", "--seed",
                               "--bounces", "--background", "--environment", "--environment-intensity", "--environment-rotation", "--threads", "--stats", "--serve", "--reference", "--checkpoint", "--validate", "--quiet"}) {
        EXPECT_NE(help.find(option), std::string::npos) << option;
    }
}

TEST(Cli, DevicesNamesLavapipe) {
    const fs::path dir = test::temp_dir("cli_devices");
    EXPECT_EQ(test::run_vkrt("devices", dir).code, 0);
    EXPECT_NE(read_file(dir / "stdout.txt").find("(lavapipe: --device lavapipe)"), std::string::npos);
}

// `devices --limits`: the limits vkrt relies on, by their Vulkan names, whether the
// device can run vkrt, and its heuristics; clamped to a profile on request.
TEST(Cli, DevicesLimitsNamesTheLimitsAndTheProfile) {
    const fs::path dir = test::temp_dir("cli_devices_limits");
    ASSERT_EQ(test::run_vkrt("devices --limits", dir).code, 0);
    const std::string own = read_file(dir / "stdout.txt");
    for (const char* piece : {"maxTexelBufferElements", "maxStorageBufferRange", "can run vkrt: yes",
                              "heuristics (cpu): submissions planned under 0.25 s"}) {
        EXPECT_NE(own.find(piece), std::string::npos) << piece << " in\n" << own;
    }
    ASSERT_EQ(test::run_vkrt("devices --limits --profile minimum", dir).code, 0);
    const std::string minimum = read_file(dir / "stdout.txt");
    EXPECT_NE(minimum.find("as profile minimum"), std::string::npos) << minimum;
    EXPECT_NE(minimum.find("maxTexelBufferElements                      65536"), std::string::npos) << minimum;
    test::expect_one_error(test::run_vkrt("devices --limits --profile nonesuch", dir),
                           {"no device profile 'nonesuch'", "minimum", "moltenvk-m1"});
}

// VKRT_DEVICE_PROFILE clamps the device for any command; --stats shows the plan it
// took, and an unknown profile is one clear error.
TEST(Cli, DeviceProfileFromTheEnvironment) {
    const fs::path dir = test::temp_dir("cli_device_profile");
    const std::string render = "render " + test::shell_quote(scene("spheres_triangles").string()) +
                               " --backend vulkan --width 16 --height 12 -q -o " +
                               test::shell_quote((dir / "out.png").string());
    ASSERT_EQ(setenv("VKRT_DEVICE_PROFILE", "minimum", 1), 0);
    const test::ProgramRun minimum =
        test::run_vkrt(render + " --stats " + test::shell_quote((dir / "s.json").string()), dir);
    ASSERT_EQ(setenv("VKRT_DEVICE_PROFILE", "nonesuch", 1), 0);
    const test::ProgramRun unknown = test::run_vkrt(render, dir);
    unsetenv("VKRT_DEVICE_PROFILE");
    EXPECT_EQ(minimum.code, 0) << minimum.stderr_text;
    EXPECT_NE(read_file(dir / "s.json").find("\"device_plan\""), std::string::npos);
    test::expect_one_error(unknown, {"no device profile 'nonesuch'", "minimum"});
}

// Without -o the image is <scene name>.png in the current directory, and the log
// names it; with -q nothing is printed at all.
TEST(Cli, DefaultOutputNameAndQuiet) {
    const fs::path dir = test::temp_dir("cli_default_output");
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    const test::ProgramRun loud = test::run_vkrt(
        "render " + test::shell_quote(scene("spheres_triangles").string()) + " --backend cpu --width 16 --height 12", dir);
    const std::string log = read_file(dir / "stdout.txt");
    fs::current_path(previous);
    EXPECT_EQ(loud.code, 0) << loud.stderr_text;
    EXPECT_TRUE(fs::exists(dir / "spheres_triangles.png"));
    EXPECT_NE(log.find("wrote     spheres_triangles.png"), std::string::npos) << log;
    EXPECT_NE(log.find("features  kept: spheres, triangles"), std::string::npos) << log;

    const test::ProgramRun quiet = test::run_vkrt("render " + test::shell_quote(scene("spheres_triangles").string()) +
                                                      " --backend cpu --width 16 --height 12 -q -o " +
                                                      test::shell_quote((dir / "q.png").string()),
                                                  dir);
    EXPECT_EQ(quiet.code, 0);
    EXPECT_EQ(read_file(dir / "stdout.txt"), "");
    EXPECT_EQ(quiet.stderr_text, "");
}

// --threads changes how the reference splits the work, never the image; on the
// Vulkan backend it is ignored with a warning.
TEST(Cli, ThreadsDoNotChangeTheImage) {
    const fs::path dir = test::temp_dir("cli_threads");
    const std::string base = "render " + test::shell_quote(scene("default").string()) + " --width 40 --height 30 -q";
    ASSERT_EQ(test::run_vkrt(base + " --backend cpu --threads 1 -o " + test::shell_quote((dir / "one.exr").string()), dir).code, 0);
    ASSERT_EQ(test::run_vkrt(base + " --backend cpu --threads 3 -o " + test::shell_quote((dir / "three.exr").string()), dir).code, 0);
    const ImageDiff d = compare_images(read_image(dir / "one.exr"), read_image(dir / "three.exr"));
    EXPECT_EQ(d.max_abs, 0.0);

    const test::ProgramRun ignored =
        test::run_vkrt(base + " --threads 2 -o " + test::shell_quote((dir / "vk.png").string()), dir);
    EXPECT_EQ(ignored.code, 0);
    EXPECT_NE(ignored.stderr_text.find("warning: --threads applies to --backend cpu only"), std::string::npos)
        << ignored.stderr_text;
}

// An NFF scene samples pixel corners (render.corners), which replaces spp: --spp
// says so instead of being dropped without a word, and the render still succeeds.
TEST(Cli, SppOnACornerSampledSceneIsAWarning) {
    const fs::path dir = test::temp_dir("cli_corners_spp");
    {
        std::ofstream nff(dir / "one.nff");
        nff << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.01\nresolution 8 8\n"
               "b 0.1 0.1 0.1\nl 2 4 6\nf 0.8 0.5 0.3 1 0 0 0 0\ns 0 0 0 1\n";
    }
    const std::string base = "render " + test::shell_quote((dir / "one.nff").string()) + " --backend cpu -q -o " +
                             test::shell_quote((dir / "one.png").string());
    const test::ProgramRun with_spp = test::run_vkrt(base + " --spp 4", dir);
    EXPECT_EQ(with_spp.code, 0) << with_spp.stderr_text;
    EXPECT_NE(with_spp.stderr_text.find("warning: --spp is ignored"), std::string::npos) << with_spp.stderr_text;
    const test::ProgramRun without = test::run_vkrt(base, dir);
    EXPECT_EQ(without.code, 0) << without.stderr_text;
    EXPECT_EQ(without.stderr_text.find("warning"), std::string::npos) << without.stderr_text;
}

// --grid reaches the stats: off, a resolution, and auto's reason.
TEST(Cli, GridOptionChoosesTheAcceleration) {
    const fs::path dir = test::temp_dir("cli_grid");
    const std::string base = "render " + test::shell_quote(scene("default").string()) +
                             " --backend cpu --width 16 --height 12 -q -o " + test::shell_quote((dir / "x.png").string()) +
                             " --stats " + test::shell_quote((dir / "s.json").string());
    auto stats = [&] { return nlohmann::json::parse(read_file(dir / "s.json")); };

    ASSERT_EQ(test::run_vkrt(base + " --grid 3x4x5", dir).code, 0);
    EXPECT_EQ(stats()["grid"]["used"], true);
    EXPECT_EQ(stats()["grid"]["resolution"], nlohmann::json::array({3, 4, 5}));
    EXPECT_GT(stats()["work"]["cells_visited"].get<double>(), 0.0);

    ASSERT_EQ(test::run_vkrt(base + " --grid off", dir).code, 0);
    EXPECT_EQ(stats()["grid"]["used"], false);
    EXPECT_EQ(stats()["work"]["cells_visited"], 0);

    // uniform: on whatever the count, no cell split.
    ASSERT_EQ(test::run_vkrt(base + " --grid uniform", dir).code, 0);
    EXPECT_EQ(stats()["grid"]["used"], true);
    EXPECT_EQ(stats()["grid"]["levels"], 0);
    EXPECT_NE(stats()["grid"]["reason"].get<std::string>().find("uniform: requested"), std::string::npos);

    // The stats say what the process held at most: more than the image's floats
    // (16 x 12 is nothing), less than this machine has.
    const double peak = stats()["memory"]["peak_resident_bytes"].get<double>();
    EXPECT_GT(peak, 1e6);
    EXPECT_LT(peak, 16e9);

    // The default scene has 5 primitives: below the threshold, auto says so.
    ASSERT_EQ(test::run_vkrt(base, dir).code, 0);
    EXPECT_EQ(stats()["grid"]["used"], false);
    EXPECT_NE(stats()["grid"]["reason"].get<std::string>().find("5 primitives, below"), std::string::npos);

    for (const char* bad : {"0x1x1", "4x4", "4x4x4x4", "fast", "70000x1x1", "4x4x"}) {
        const test::ProgramRun run = test::run_vkrt(base + " --grid " + bad, dir);
        EXPECT_EQ(run.code, 1) << bad;
        EXPECT_NE(run.stderr_text.find("--grid: expected auto, on, off, uniform or NXxNYxNZ"), std::string::npos)
            << run.stderr_text;
    }
}

}  // namespace

namespace {

// OpenImageIO (some 260 shared libraries) loads only for the formats that need it
// (image/image_files.hpp): not for --version, nor for a render to PNG.
TEST(Cli, APngRenderLoadsNoImageLibrary) {
    const fs::path dir = test::temp_dir("cli_no_oiio");
    setenv("LD_DEBUG", "files", 1);
    const test::ProgramRun version = test::run_vkrt("--version", dir);
    const test::ProgramRun png = test::run_vkrt(
        "render " + test::shell_quote(scene("default").string()) + " --width 16 --height 16 -q -o " +
            test::shell_quote((dir / "x.png").string()),
        dir);
    const test::ProgramRun exr = test::run_vkrt(
        "render " + test::shell_quote(scene("default").string()) + " --width 16 --height 16 -q -o " +
            test::shell_quote((dir / "x.exr").string()),
        dir);
    unsetenv("LD_DEBUG");
    EXPECT_EQ(version.stderr_text.find("libOpenImageIO"), std::string::npos);
    EXPECT_EQ(png.code, 0);
    EXPECT_EQ(png.stderr_text.find("libOpenImageIO"), std::string::npos);
    EXPECT_EQ(exr.code, 0);
    EXPECT_NE(exr.stderr_text.find("libOpenImageIO"), std::string::npos) << "the check itself sees the library";
    EXPECT_EQ(read_image(dir / "x.png").width, 16u);
}

}  // namespace

namespace {

// --reference: the summary gives the error against the reference, 0 for the very
// same render, and a reference of another size is refused before rendering.
TEST(Cli, ReferenceGivesTheErrorInTheSummary) {
    const fs::path dir = test::temp_dir("cli_reference");
    const std::string render = "render " + test::shell_quote(scene("area_light").string()) + " --width 40 --height 30";
    ASSERT_EQ(test::run_vkrt(render + " -q -o " + test::shell_quote((dir / "ref.exr").string()), dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + " -o " + test::shell_quote((dir / "again.exr").string()) + " --reference " +
                                 test::shell_quote((dir / "ref.exr").string()),
                             dir)
                  .code,
              0);
    EXPECT_NE(read_file(dir / "stdout.txt").find("error     RMSE 0, relMSE 0,"), std::string::npos)
        << read_file(dir / "stdout.txt");
    test::expect_one_error(test::run_vkrt("render " + test::shell_quote(scene("area_light").string()) +
                                              " --width 41 --height 30 -o " +
                                              test::shell_quote((dir / "other.png").string()) + " --reference " +
                                              test::shell_quote((dir / "ref.exr").string()),
                                          dir),
                           {"--reference", "is 40x30 but the render is 41x30"});
    EXPECT_FALSE(fs::exists(dir / "other.png"));
}

// --sampler overrides the scene's render.sampler: sobol is the default, hash draws
// other numbers, so another image of the same scene.
TEST(Cli, SamplerOptionPicksTheRandomNumbers) {
    const fs::path dir = test::temp_dir("cli_sampler");
    const std::string render =
        "render " + test::shell_quote(scene("area_light").string()) + " --backend cpu --width 40 --height 30 -q -o ";
    auto out = [&](const char* name) { return test::shell_quote((dir / name).string()); };
    ASSERT_EQ(test::run_vkrt(render + out("default.exr"), dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("sobol.exr") + " --sampler sobol", dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("hash.exr") + " --sampler hash", dir).code, 0);
    ASSERT_EQ(test::run_vkrt("compare " + out("default.exr") + " " + out("sobol.exr") + " --max-abs 0", dir).code, 0);
    EXPECT_NE(test::run_vkrt("compare " + out("default.exr") + " " + out("hash.exr") + " --max-abs 0", dir).code, 0);
}

// --background sets the radiance of rays that miss, one number for all channels or
// three; --bounces the path length of global mode.
TEST(Cli, BackgroundAndBouncesOverrideTheScene) {
    const fs::path dir = test::temp_dir("cli_background");
    const std::string render =
        "render " + test::shell_quote(scene("gallery/k_room").string()) + " --backend cpu --width 24 --height 18 --spp 2 -q -o ";
    auto out = [&](const char* name) { return test::shell_quote((dir / name).string()); };
    ASSERT_EQ(test::run_vkrt(render + out("default.exr"), dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("grey.exr") + " --background 0.5", dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("grey3.exr") + " --background 0.5,0.5,0.5", dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("short.exr") + " --bounces 0", dir).code, 0);
    EXPECT_EQ(test::run_vkrt("compare " + out("grey.exr") + " " + out("grey3.exr") + " --max-abs 0", dir).code, 0);
    EXPECT_NE(test::run_vkrt("compare " + out("default.exr") + " " + out("grey.exr") + " --max-abs 0", dir).code, 0);
    EXPECT_NE(test::run_vkrt("compare " + out("default.exr") + " " + out("short.exr") + " --max-abs 0", dir).code, 0);
}

// --environment puts an image around a scene, or replaces the scene's; intensity
// and rotation change it; --background takes its place. Mistakes are refused.
TEST(Cli, EnvironmentOptionsOverrideTheScene) {
    const fs::path dir = test::temp_dir("cli_environment");
    const std::string sky = test::shell_quote((test::source_dir() / "scenes" / "environment" / "sky.hdr").string());
    const std::string render = "render " + test::shell_quote(scene("environment").string()) +
                               " --backend cpu --width 24 --height 16 --spp 2 -q -o ";
    auto out = [&](const char* name) { return test::shell_quote((dir / name).string()); };
    ASSERT_EQ(test::run_vkrt(render + out("scene.exr"), dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("given.exr") + " --environment " + sky, dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("turned.exr") + " --environment-rotation 90", dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("dim.exr") + " --environment-intensity 0.5", dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("grey.exr") + " --background 0.5", dir).code, 0);
    EXPECT_EQ(test::run_vkrt("compare " + out("scene.exr") + " " + out("given.exr") + " --max-abs 0", dir).code, 0);
    for (const char* other : {"turned.exr", "dim.exr", "grey.exr"}) {
        EXPECT_NE(test::run_vkrt("compare " + out("scene.exr") + " " + out(other) + " --max-abs 0", dir).code, 0) << other;
    }
    test::expect_one_error(test::run_vkrt(render + out("x.exr") + " --environment " + sky + " --background 1", dir),
                           {"--environment", "--background"});
    test::expect_one_error(test::run_vkrt(render + out("x.exr") + " --environment-intensity 2e6", dir),
                           {"--environment-intensity", "2e6"});
    test::expect_one_error(test::run_vkrt(render + out("x.exr") + " --environment-rotation ninety", dir),
                           {"--environment-rotation", "ninety"});
    test::expect_one_error(test::run_vkrt(render + out("x.exr") + " --environment nonesuch.hdr", dir),
                           {"--environment", "nonesuch.hdr", "no such file"});
    test::expect_one_error(test::run_vkrt("render " + test::shell_quote(scene("area_light").string()) +
                                              " --backend cpu -q -o " + out("x.exr") + " --environment-intensity 2",
                                          dir),
                           {"--environment-intensity", "no environment image"});
}

// --exposure and --tonemap change an 8-bit output and leave a float one alone; merge
// takes them too; a bad value is refused with what was expected.
TEST(Cli, DisplayOptionsShapeEightBitOutputsOnly) {
    const fs::path dir = test::temp_dir("cli_display");
    const std::string render =
        "render " + test::shell_quote(scene("area_light").string()) + " --backend cpu --width 40 --height 30 -q -o ";
    auto out = [&](const char* name) { return test::shell_quote((dir / name).string()); };
    ASSERT_EQ(test::run_vkrt(render + out("plain.png"), dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("shown.png") + " --exposure 1 --tonemap filmic", dir).code, 0);
    EXPECT_NE(test::run_vkrt("compare " + out("plain.png") + " " + out("shown.png") + " --max-abs 0", dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("plain.exr"), dir).code, 0);
    ASSERT_EQ(test::run_vkrt(render + out("shown.exr") + " --exposure 1 --tonemap filmic", dir).code, 0);
    EXPECT_EQ(test::run_vkrt("compare " + out("plain.exr") + " " + out("shown.exr") + " --max-abs 0", dir).code, 0);

    ASSERT_EQ(test::run_vkrt(render + out("part.exr") + " --samples 0:4", dir).code, 0);
    EXPECT_EQ(test::run_vkrt("merge " + out("part.exr") + " -q --tonemap filmic -o " + out("merged.png"), dir).code, 0);

    const test::ProgramRun bad = test::run_vkrt(render + out("x.png") + " --exposure 65", dir);
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.stderr_text.find("expected a number of stops from -64 to 64, got '65'"), std::string::npos)
        << bad.stderr_text;
    const test::ProgramRun curve = test::run_vkrt(render + out("x.png") + " --tonemap aces", dir);
    EXPECT_EQ(curve.code, 1);
    EXPECT_NE(curve.stderr_text.find("--tonemap"), std::string::npos) << curve.stderr_text;
}

// compare's --metric prints each metric named, --difference draws A - B; a metric it
// does not know, a difference image that is not a PNG, and SSIM of images smaller
// than its window are refused.
TEST(Cli, CompareMetricsAndDifferenceImage) {
    const fs::path dir = test::temp_dir("cli_compare_metrics");
    Image a(12, 12), b(12, 12);
    for (float& v : a.rgb) v = 0.5f;
    for (float& v : b.rgb) v = 0.25f;
    write_image(a, dir / "a.exr");
    write_image(b, dir / "b.exr");
    write_image(Image(4, 4), dir / "small.exr");
    const std::string pair = test::shell_quote((dir / "a.exr").string()) + " " + test::shell_quote((dir / "b.exr").string());
    const test::ProgramRun run = test::run_vkrt(
        "compare " + pair + " --metric mae,relmse,ssim --difference " + test::shell_quote((dir / "d.png").string()), dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    const std::string out = read_file(dir / "stdout.txt");
    EXPECT_NE(out.find("\nmae 0.25\n"), std::string::npos) << out;
    EXPECT_NE(out.find("\nrelmse 0.862069\n"), std::string::npos) << out;  // 0.0625 / (0.25^2 + 0.01)
    EXPECT_NE(out.find("\nssim 0.800"), std::string::npos) << out;  // (2 ab + 1e-4) / (a^2 + b^2 + 1e-4)
    EXPECT_NE(out.find("difference A - B from -0.25 (blue) to 0.25 (red)"), std::string::npos) << out;
    const Image d = read_image(dir / "d.png");
    EXPECT_NEAR(d.pixel(3, 3)[0], 180.0 / 255.0, 1e-6) << "all red: A is above B by the whole range";

    test::expect_one_error(test::run_vkrt("compare " + pair + " --metric psnr", dir), {"--metric", "psnr"});
    test::expect_one_error(test::run_vkrt("compare " + pair + " --difference-range 1", dir), {"--difference-range", "--difference"});
    const test::ProgramRun jpeg = test::run_vkrt("compare " + pair + " --difference " + test::shell_quote((dir / "d.jpg").string()), dir);
    EXPECT_EQ(jpeg.code, 2);
    EXPECT_NE(jpeg.stderr_text.find("name a .png file"), std::string::npos) << jpeg.stderr_text;
    const test::ProgramRun small = test::run_vkrt(
        "compare " + test::shell_quote((dir / "small.exr").string()) + " " + test::shell_quote((dir / "small.exr").string()) +
            " --metric ssim",
        dir);
    EXPECT_EQ(small.code, 2);
    EXPECT_NE(small.stderr_text.find("at least 11 x 11 pixels"), std::string::npos) << small.stderr_text;
}

// compare --test: 0 when A - B is within the noise A's variance layer states, 1 when
// not, 2 when A carries no variance; a partial file carries its own; --p-values.
TEST(Cli, CompareTestTellsNoiseFromDifference) {
    const fs::path dir = test::temp_dir("cli_compare_test");
    Image a(12, 12), near(12, 12), far(12, 12);
    for (float& v : a.rgb) v = 0.5f;
    for (float& v : near.rgb) v = 0.52f;  // z = -0.2
    for (float& v : far.rgb) v = 1.0f;    // z = -5, p = 5.7e-7, below the level of 432 tests, 2.3e-5
    ImageLayer variance{"variance", {"R", "G", "B"}, std::vector<float>(a.rgb.size(), 0.01f)};
    write_layered_exr(a, {variance}, dir / "a.exr");
    write_image(near, dir / "near.exr");
    write_image(far, dir / "far.exr");
    const auto quoted = [&](const char* name) { return test::shell_quote((dir / name).string()); };
    const test::ProgramRun consistent =
        test::run_vkrt("compare " + quoted("a.exr") + " " + quoted("near.exr") + " --test --p-values " + quoted("p.exr"), dir);
    EXPECT_EQ(consistent.code, 0) << consistent.stderr_text;
    std::string out = read_file(dir / "stdout.txt");
    EXPECT_NE(out.find("432 of 432 pixel channels and the 3 image means tested (A's variance its own, B's taken as exact)"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("consistent: the difference is within the images' noise"), std::string::npos) << out;
    EXPECT_NEAR(read_image(dir / "p.exr").rgb[0], std::erfc(0.2 / std::sqrt(2.0)), 1e-5);

    const test::ProgramRun rejected = test::run_vkrt("compare " + quoted("a.exr") + " " + quoted("far.exr") + " --test", dir);
    EXPECT_EQ(rejected.code, 1) << rejected.stderr_text;
    out = read_file(dir / "stdout.txt");
    EXPECT_NE(out.find("rejected: 432 pixel channels and 3 image means differ by more than their noise explains"),
              std::string::npos)
        << out;

    const test::ProgramRun unusable = test::run_vkrt("compare " + quoted("near.exr") + " " + quoted("a.exr") + " --test", dir);
    EXPECT_EQ(unusable.code, 2);
    EXPECT_NE(unusable.stderr_text.find("--test needs the variance of A's pixel means"), std::string::npos)
        << unusable.stderr_text;
    test::expect_one_error(test::run_vkrt("compare " + quoted("a.exr") + " " + quoted("near.exr") + " --alpha 0.05", dir),
                           {"--alpha", "--test"});
    const test::ProgramRun png =
        test::run_vkrt("compare " + quoted("a.exr") + " " + quoted("near.exr") + " --test --p-values " + quoted("p.png"), dir);
    EXPECT_EQ(png.code, 2);
    EXPECT_NE(png.stderr_text.find("--p-values writes an OpenEXR file"), std::string::npos) << png.stderr_text;
    test::expect_one_error(test::run_vkrt("compare " + quoted("a.exr") + " " + quoted("near.exr") + " --test --alpha 0.9", dir),
                           {"--alpha"});

    // A partial file's sums of squares give its variance.
    std::ofstream(dir / "tiny.json") << R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 40, "width": 4, "height": 4 },
      "render": { "mode": "global", "background": [0.5, 0.5, 0.5] },
      "materials": { "m": { "diffuse": [0.5, 0.5, 0.5] } },
      "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ] })";
    const test::ProgramRun partial = test::run_vkrt(
        "render " + quoted("tiny.json") + " --backend cpu --samples 0:16 -q -o " + quoted("part.exr"), dir);
    ASSERT_EQ(partial.code, 0) << partial.stderr_text;
    const test::ProgramRun self = test::run_vkrt("compare " + quoted("part.exr") + " " + quoted("part.exr") + " --test", dir);
    EXPECT_EQ(self.code, 0) << self.stderr_text;
    out = read_file(dir / "stdout.txt");
    EXPECT_NE(out.find("(A's variance its own, B's its own)"), std::string::npos) << out;
}

}  // namespace
