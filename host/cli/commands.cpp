#include "cli/commands.hpp"

#include <fstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/progress.hpp"
#include "gpu/vulkan_backend.hpp"
#include "image/compare.hpp"
#include "ref/ref_backend.hpp"
#include "render/render.hpp"
#include "render/stats_json.hpp"
#include "scene/limits.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"

namespace vkrt::cli {
namespace {

std::unique_ptr<Backend> make_backend(const RenderArgs& args) {
    if (args.backend == "cpu") {
        return make_reference_backend(args.threads);
    }
    return make_vulkan_backend(VulkanOptions{args.device, args.validate});
}

void apply_overrides(const RenderArgs& args, Scene& scene) {
    if (args.width) scene.camera.width = *args.width;
    if (args.height) scene.camera.height = *args.height;
    if (args.spp) scene.render.spp = *args.spp;
    if (args.seed) scene.render.seed = *args.seed;
    const std::uint64_t pixels = std::uint64_t(scene.camera.width) * scene.camera.height;
    if (pixels > limits::kMaxImagePixels) {
        throw SceneError(fmt::format("--width/--height: image of {}x{} pixels is larger than the limit of {} pixels",
                                     scene.camera.width, scene.camera.height, limits::kMaxImagePixels));
    }
}

std::string default_output(const std::string& scene) {
    return std::filesystem::path(scene).stem().string() + ".png";
}

void print_summary(const RenderStats& s, const std::string& output) {
    fmt::print("backend   {} on {}\n", s.backend, s.device);
    fmt::print("image     {}x{}, {} samples per pixel\n", s.width, s.height, s.samples_per_pixel);
    fmt::print("features  kept: {}; left out: {}\n", fmt::join(s.features.kept(), ", "),
               fmt::join(s.features.left_out(), ", "));
    fmt::print("rays      {} ({} eye, {} shadow), {:.2f} Mrays/s\n", s.rays(), s.eye_rays, s.shadow_rays,
               s.render_seconds > 0.0 ? double(s.rays()) / s.render_seconds * 1e-6 : 0.0);
    fmt::print("seconds   setup {:.3f}, render {:.3f}, total {:.3f}\n", s.flatten_seconds + s.setup_seconds,
               s.render_seconds, s.total_seconds);
    fmt::print("wrote     {}\n", output);
}

}  // namespace

int run_render(const RenderArgs& args) {
    Scene scene = load_scene(args.scene);
    apply_overrides(args, scene);
    const std::string output = args.output.empty() ? default_output(args.scene) : args.output;

    auto backend = make_backend(args);
    ProgressReporter progress("rendering", !args.quiet);
    RenderOutcome outcome = render_scene(scene, *backend, [&](std::uint32_t done, std::uint32_t total) {
        progress.update(done, total);
    });
    progress.finish();
    write_image(outcome.image, output);

    const RenderStats& s = outcome.stats;
    if (!args.stats_file.empty()) {
        std::ofstream out(args.stats_file);
        out << stats_to_json(s).dump(2) << '\n';
        if (!out) throw std::runtime_error(fmt::format("{}: cannot write the stats file", args.stats_file));
    }
    if (!args.quiet) print_summary(s, output);

    if (s.nonfinite_samples > 0) {
        fmt::print(stderr, "warning: {} samples were NaN or infinite and were left out of the average\n",
                   s.nonfinite_samples);
    }
    if (s.validation_messages > 0) {
        throw std::runtime_error(fmt::format("the Vulkan validation layer reported {} messages (above)",
                                             s.validation_messages));
    }
    if (s.truncated_samples > 0) {
        throw std::runtime_error(fmt::format(
            "{} samples ran out of the per-invocation loop budget of {} iterations and were left out; "
            "the image ({}) is incomplete. The scene has too many primitives for brute-force tracing in one "
            "invocation (lavapipe stops loops silently at 65,535 iterations)",
            s.truncated_samples, scene.render.loop_budget != 0 ? scene.render.loop_budget : kernel::DEFAULT_LOOP_BUDGET,
            output));
    }
    return 0;
}

int run_compare(const CompareArgs& args) {
    const Image a = read_image(args.a);
    const Image b = read_image(args.b);
    const ImageDiff d = compare_images(a, b, args.threshold);
    fmt::print("RMSE {:.6g}, max abs {:.6g}, PSNR {:.2f} dB, {} of {} pixels ({:.4f}%) differ by more than {:g}\n",
               d.rmse, d.max_abs, d.psnr, d.pixels_over, d.pixels, d.fraction_over() * 100.0, args.threshold);
    bool over = false;
    if (args.max_rmse && d.rmse > *args.max_rmse) {
        fmt::print("over bound: RMSE {:.6g} > {:g}\n", d.rmse, *args.max_rmse);
        over = true;
    }
    if (args.max_abs && d.max_abs > *args.max_abs) {
        fmt::print("over bound: max abs {:.6g} > {:g}\n", d.max_abs, *args.max_abs);
        over = true;
    }
    return over ? 1 : 0;
}

int run_devices() {
    const auto devices = list_vulkan_devices();
    for (const DeviceInfo& d : devices) {
        fmt::print("{}: {} [{}] driver {}, Vulkan {}\n", d.index, d.name, d.type, d.driver, d.api_version);
    }
    if (devices.empty()) fmt::print("no Vulkan devices\n");
    return 0;
}

}  // namespace vkrt::cli
