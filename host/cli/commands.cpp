#include "cli/commands.hpp"

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>
#include <chrono>
#include <future>
#include <optional>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "probe/float_profile_json.hpp"
#include "probe/float_profile_table.hpp"
#include "app/output_paths.hpp"
#include "app/peak_memory.hpp"
#include "app/preparation_progress.hpp"
#include "app/progress.hpp"
#include "gpu/float_probe.hpp"
#include "gpu/vulkan_backend.hpp"
#include "image/compare.hpp"
#include "image/error_image.hpp"
#include "image/ssim.hpp"
#include "image/error_metrics.hpp"
#include "image/image_files.hpp"
#include "image/stack.hpp"
#include "image/z_test.hpp"
#include "live/live_server.hpp"
#include "live/pass_feed.hpp"
#include "probe/cpu_float_probe.hpp"
#include "probe/float_profile.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/partial_file.hpp"
#include "render/render.hpp"
#include "render/sample_ranges.hpp"
#include "render/stats_json.hpp"
#include "scene/estimator_spec.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/limits.hpp"
#include "scene/load_scene.hpp"
#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"

namespace vkrt::cli {
namespace {

std::unique_ptr<Backend> make_backend(const RenderArgs& args) {
    if (args.backend == "cpu") {
        return make_cpu_backend(args.threads);
    }
    return make_vulkan_backend(VulkanOptions{args.device, args.validate});
}

void apply_overrides(const RenderArgs& args, Scene& scene) {
    if (args.width) scene.camera.width = *args.width;
    if (args.height) scene.camera.height = *args.height;
    // A view framed to the model frames it again for the image's new shape.
    if (scene.camera.framed && (args.width || args.height)) frame_scene(scene);
    if (args.spp) scene.render.spp = *args.spp;
    if (args.spp && scene.render.corners) {
        fmt::print(stderr, "warning: --spp is ignored: this scene traces one ray through every pixel corner "
                           "(render.corners, on for NFF scenes), which replaces aa and spp\n");
    }
    if (args.variance && scene.render.corners) {
        throw std::runtime_error("--variance: this scene traces one ray through every pixel corner (render.corners, "
                                 "on for NFF scenes): its pixels average four rays, not samples, and have no variance");
    }
    if (!args.passes.empty() && scene.render.corners) {
        throw std::runtime_error("--passes: this scene traces one ray through every pixel corner (render.corners, on "
                                 "for NFF scenes), not through its pixels: it has no passes");
    }
    scene.render.squares = args.variance || !args.samples.empty();
    scene.render.passes = !args.passes.empty();
    if (args.seed) scene.render.seed = *args.seed;
    if (!args.sampler.empty()) scene.render.sampler = parse_sampler(args.sampler).value();  // checked by the parser
    if (args.bounces) scene.render.max_bounces = *args.bounces;
    if (!args.background.empty()) {
        const std::array<double, 3> c = parse_colour(args.background);  // checked by the parser
        scene.render.background = glm::dvec3(c[0], c[1], c[2]);
        scene.environment.reset();
    }
    if (!args.environment.empty()) {
        std::vector<std::string> warnings;
        scene.environment = load_environment(args.environment, "--environment", warnings);
        for (const std::string& warning : warnings) fmt::print(stderr, "warning: {}\n", warning);
    }
    if (args.environment_intensity || args.environment_rotation) {
        if (!scene.environment) {
            throw SceneError("--environment-intensity/--environment-rotation: the scene has no environment image "
                             "(give one with --environment)");
        }
        if (args.environment_intensity) scene.environment->intensity = *args.environment_intensity;
        if (args.environment_rotation) scene.environment->rotation = *args.environment_rotation;
    }
    scene.render.display = display_with(scene.render.display, args.display);
    if (!args.grid.empty()) {
        const GridSettings grid = parse_grid_option(args.grid).value();  // checked by the parser
        if (args.grid == "on" || args.grid == "uniform") {
            scene.render.grid.mode = grid.mode;  // keeps a resolution the scene gives
        } else {
            scene.render.grid = grid;
        }
    }
    if (const std::string problem =
            limits::image_size_problem(scene.camera.width, scene.camera.height, scene.render.corners);
        !problem.empty()) {
        throw SceneError("--width/--height: " + problem);
    }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void warn_ignored_options(const RenderArgs& args) {
    if (args.backend == "vulkan" && args.threads != 0) {
        fmt::print(stderr, "warning: --threads applies to --backend cpu only; ignored\n");
    }
    if (args.backend == "cpu" && (!args.device.empty() || args.validate)) {
        fmt::print(stderr, "warning: --device and --validate apply to --backend vulkan only; ignored\n");
    }
}

std::string progress_detail(const ProgressiveStatus& status) {
    return fmt::format("{} spp, {:.3g} spp/s", status.whole_samples, status.samples_per_second());
}

// <scene name>.png, or for a partial render <scene name>_A-B.exr.
std::string default_output(const std::string& scene, const std::optional<SampleRange>& samples) {
    const std::string stem = scene_stem(scene);
    return samples ? fmt::format("{}_{}-{}.exr", stem, samples->first, samples->end()) : stem + ".png";
}

// The render's output: the image, or for --samples the partial file of the samples
// done so far. Written whole or not at all, also when it replaces a checkpoint.
// `resolved`: the image of `sums` where the caller has it already (a full-size
// image costs a pass over every pixel to make).
void write_output(const std::string& output, const RenderArgs& args, const Scene& scene, const std::string& backend,
                  const RenderResult& sums, const std::optional<SampleRange>& samples, std::uint32_t samples_done,
                  std::uint64_t fingerprint, bool corners, const Image* resolved = nullptr) {
    app::write_atomically(output, [&](const std::filesystem::path& file) {
        if (samples) {
            write_partial(PartialFile{sums, {SampleRange{samples->first, samples_done}},
                                      std::filesystem::path(args.scene).filename().string(), scene.render.seed,
                                      fingerprint, backend, corners},
                          file);
        } else if (args.variance || !args.passes.empty()) {
            std::vector<ImageLayer> layers;
            if (args.variance) layers.push_back(variance_layer(sums));
            if (!args.passes.empty()) {
                for (ImageLayer& layer : pass_layers(sums, parse_passes(args.passes))) layers.push_back(std::move(layer));
            }
            write_layered_exr(resolved != nullptr ? *resolved : resolve_image(sums, corners), layers, file);
        } else {
            write_image(resolved != nullptr ? *resolved : resolve_image(sums, corners), file, scene.render.display);
        }
    });
}

void print_summary(const RenderStats& s, const std::string& output, bool partial) {
    fmt::print("backend   {} on {}\n", s.backend, s.device);
    const std::string range = partial ? fmt::format("samples {}:{}, ", s.first_sample, s.first_sample + s.samples_per_pixel)
                                      : std::string();
    fmt::print("image     {}x{}, {}{} samples per pixel in {} pass{}{}\n", s.width, s.height, range,
               s.samples_per_pixel, s.passes, s.passes == 1 ? "" : "es",
               s.stopped_by_request ? " (stopped from the live preview)"
               : s.stopped_by_time  ? " (stopped by --time)"
                                    : "");
    auto list = [](const std::vector<std::string>& names) {
        return names.empty() ? std::string("(none)") : fmt::format("{}", fmt::join(names, ", "));
    };
    fmt::print("features  kept: {}; left out: {}\n", list(s.features.kept()), list(s.features.left_out()));
    if (s.triangles + s.textures + s.emitters > 0) {
        fmt::print("scene     {} triangles, {} area lights, {} textures ({:.1f} MiB of texels)\n", s.triangles, s.emitters,
                   s.textures, double(s.texture_bytes) / (1 << 20));
    }
    fmt::print("rays      {} ({} eye of which {} hit, {} shadow, {} reflection, {} refraction, {} bounce), "
               "{:.2f} Mrays/s\n",
               s.rays(), s.eye_rays, s.eye_hits, s.shadow_rays, s.reflection_rays, s.refraction_rays, s.bounce_rays,
               s.render_seconds > 0.0 ? double(s.rays()) / s.render_seconds * 1e-6 : 0.0);
    if (s.features.has(Feature::HAS_GLOBAL)) {
        fmt::print("paths     {} ended by Russian roulette, {} samples dropped by the paper estimator (gl() = 0)\n",
                   s.roulette_ended, s.paper_dropped);
    }
    if (s.dropped_low_weight + s.dropped_stack_full > 0) {
        fmt::print("ray tree  {} secondary rays left out for weighing under render.min_weight, {} for a full stack\n",
                   s.dropped_low_weight, s.dropped_stack_full);
    }
    if (s.grid.used) {
        fmt::print("grid      {}x{}x{} root cells, {} levels of splits, {} leaf cells, {} references, {:.1f} MiB, "
                   "built in {:.3f} s ({})\n",
                   s.grid.resolution[0], s.grid.resolution[1], s.grid.resolution[2], s.grid.levels, s.grid.cells,
                   s.grid.references, double(s.grid.bytes) / (1 << 20), s.grid.build_seconds, s.grid.reason);
    } else {
        fmt::print("grid      not used ({})\n", s.grid.reason);
    }
    fmt::print("per ray   {:.2f} cells visited, {:.2f} intersection tests\n", s.per_ray(s.cells_visited),
               s.per_ray(s.intersection_tests));
    fmt::print("seconds   load {:.3f} (textures {:.3f}), setup {:.3f}, first pass done at {:.3f}, render {:.3f}, passes "
               "{:.3f}, total {:.3f}\n",
               s.load_seconds, s.decode_seconds, s.flatten_seconds + s.setup_seconds, s.first_pass_seconds,
               s.render_seconds, s.pass_seconds, s.total_seconds);
    if (s.peak_resident_bytes > 0) fmt::print("memory    peak {:.0f} MiB resident\n", double(s.peak_resident_bytes) / (1 << 20));
    fmt::print("wrote     {}{}\n", output, partial ? " (a partial file: vkrt merge adds it up with others)" : "");
}

// The backend, made on another thread while the scene loads: neither needs the
// other, and a Vulkan instance and device take as long as reading a large scene
// file. `seconds` gets how long it took. A scene's error is still the one reported
// (the future waits, its own is dropped).
std::future<std::unique_ptr<Backend>> make_backend_meanwhile(const RenderArgs& args, double& seconds) {
    return std::async(std::launch::async, [&args, &seconds] {
        const auto made = std::chrono::steady_clock::now();
        std::unique_ptr<Backend> b = make_backend(args);
        seconds = seconds_since(made);
        return b;
    });
}

// The scene's own warnings, then the command line's changes to it.
void prepare_scene(const RenderArgs& args, Scene& scene) {
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "warning: {}\n", warning);
    apply_overrides(args, scene);
}

// Where the render goes: the image, or for --samples the partial file of those samples.
struct RenderTarget {
    std::optional<SampleRange> samples;
    std::string output;
};

// The render's target, its paths (and the stats file's) checked now rather than
// after a long render.
RenderTarget render_target(const RenderArgs& args) {
    RenderTarget target;
    // The range is checked by the parser.
    if (!args.samples.empty()) target.samples = parse_sample_range(args.samples, limits::kMaxSpp);
    target.output = args.output.empty() ? default_output(args.scene, target.samples) : args.output;
    app::check_writable_image(target.output);
    if (target.samples && !app::is_exr(target.output)) {
        throw std::runtime_error(fmt::format(
            "{}: --samples writes a partial file, which is OpenEXR: give -o a name ending in .exr", target.output));
    }
    if (args.variance && (target.samples || !app::is_exr(target.output))) {
        throw std::runtime_error(fmt::format(
            "{}: {}", target.output,
            target.samples ? "--variance writes the variance beside a whole image; a partial file (--samples) carries "
                             "the sums of squares it is made from"
                           : "--variance writes its layer into an OpenEXR file: give -o a name ending in .exr"));
    }
    if (!args.passes.empty() && (target.samples || !app::is_exr(target.output))) {
        throw std::runtime_error(fmt::format(
            "{}: {}", target.output,
            target.samples ? "--passes writes its layers beside a whole image; a partial file (--samples) carries "
                             "none"
                           : "--passes writes its layers into an OpenEXR file: give -o a name ending in .exr"));
    }
    if (!args.stats_file.empty()) app::check_writable_file(args.stats_file, "stats file");
    return target;
}

// How many samples the passes render: the scene's (--spp changed it), as many as
// --time allows, or those of --samples.
RenderPlan sample_plan(const RenderArgs& args, const std::optional<SampleRange>& samples) {
    RenderPlan plan;
    plan.seconds = args.time;
    // A time budget alone renders as many samples as fit, up to the most a pixel takes.
    if (args.time && !args.spp) plan.samples = limits::kMaxSpp;
    if (samples) {
        plan.first_sample = samples->first;
        plan.samples = samples->count;
    }
    return plan;
}

// When the command's steps ended, from its start.
struct CommandTimes {
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    double backend_seconds = 0.0;  // making the backend, while the scene loaded
    double load_seconds = 0.0;
    std::optional<double> first_pass_seconds;
};

// The stats only the command knows: its times (the backend's setup counted in the
// render's), the textures' decoding, and the peak memory.
void add_command_stats(RenderStats& s, const CommandTimes& times, const Scene& scene) {
    s.setup_seconds += times.backend_seconds;
    s.load_seconds = times.load_seconds;
    s.decode_seconds = scene.texture_decode_seconds;
    s.first_pass_seconds = times.first_pass_seconds.value_or(0.0);
    s.total_seconds = seconds_since(times.start);  // from loading the scene to the written image
    s.peak_resident_bytes = app::peak_resident_bytes();
}

void write_stats_file(const std::string& file, const RenderStats& s) {
    std::ofstream out(file);
    out << stats_to_json(s).dump(2) << '\n';
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the stats file", file));
}

// The summary and, given --reference, the error against it; nothing with --quiet.
void print_report(const RenderArgs& args, const RenderStats& s, const RenderTarget& target, const Image& image,
                  const Image& reference) {
    if (args.quiet) return;
    print_summary(s, target.output, target.samples.has_value());
    if (!args.reference.empty()) {
        const ErrorMetrics error = error_metrics(image, reference);
        fmt::print("error     RMSE {:.6g}, relMSE {:.6g}, mean {:.6g} against {:.6g} of {}\n", error.rmse, error.relmse,
                   error.mean, error.mean - error.mean_diff, args.reference);
    }
}

// The live preview's last word: the outcome, and the file written.
void finish_live_preview(live::LiveFeed& feed, const RenderOutcome& outcome, const std::string& label,
                         const std::string& output) {
    live::feed_outcome(feed, outcome, label);
    feed.finish(output);
    feed.wait_until_seen(2.0);
}

// What the render left out or made coarser: said on stderr, since the summary may
// be --quiet.
void warn_about_render(const RenderStats& s) {
    if (s.nonfinite_samples > 0) {
        fmt::print(stderr, "warning: {} samples were NaN or infinite and were left out of the average\n",
                   s.nonfinite_samples);
    }
    // A grid coarser than the scene or --grid asked for renders the same image, only slower.
    if (!s.grid.warning.empty()) fmt::print(stderr, "warning: {}\n", s.grid.warning);
    if (s.clamped_samples > 0) {
        fmt::print(stderr, "warning: {} samples had a radiance above {:.3g} and were clamped to it\n",
                   s.clamped_samples, double(kernel::SUM_SAMPLE_MAX));
    }
}

// The failures found only once the image is written: validation messages, and
// samples cut short by the loop budget.
void check_render_complete(const RenderStats& s, const std::string& output) {
    if (s.validation_messages > 0) {
        throw std::runtime_error(fmt::format("the Vulkan validation layer reported {} messages (above)",
                                             s.validation_messages));
    }
    if (s.truncated_samples > 0) {
        throw std::runtime_error(fmt::format(
            "{} samples ran out of the per-invocation loop budget of {} iterations and were left out; "
            "the image ({}) is incomplete (lavapipe stops loops silently at 65,535 iterations per 8-lane "
            "vector, so the kernel stops first, or flags what lavapipe cut). {}",
            s.truncated_samples, s.loop_budget, output,
            s.grid.used ? "Grid cells along these rays hold too many primitives, or a sample traces too many "
                          "rays through them: try a finer render.grid resolution or a lower render.max_depth"
                        : "The scene has too many primitives for brute-force tracing: try --grid on"));
    }
}

}  // namespace

std::vector<RenderPass> parse_passes(const std::string& text) {
    static const std::array<std::pair<const char*, RenderPass>, 3> kNames = {
        {{"albedo", RenderPass::Albedo}, {"normal", RenderPass::Normal}, {"depth", RenderPass::Depth}}};
    std::vector<RenderPass> passes;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::string name = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const auto it = std::find_if(kNames.begin(), kNames.end(), [&](const auto& n) { return name == n.first; });
        if (it == kNames.end()) {
            throw std::invalid_argument(
                fmt::format("expected albedo, normal or depth, separated by commas, got '{}' in '{}'", name, text));
        }
        if (std::find(passes.begin(), passes.end(), it->second) != passes.end()) {
            throw std::invalid_argument(fmt::format("'{}' is named twice in '{}'", name, text));
        }
        passes.push_back(it->second);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return passes;
}

std::optional<GridSettings> parse_grid_option(const std::string& text) {
    if (text == "auto") return GridSettings{GridMode::Auto, {0, 0, 0}};
    if (text == "on") return GridSettings{GridMode::On, {0, 0, 0}};
    if (text == "off") return GridSettings{GridMode::Off, {0, 0, 0}};
    if (text == "uniform") return GridSettings{GridMode::Uniform, {0, 0, 0}};
    GridSettings g{GridMode::On, {0, 0, 0}};
    std::size_t pos = 0;
    for (int a = 0; a < 3; ++a) {
        if (a > 0) {
            if (pos >= text.size() || text[pos] != 'x') return std::nullopt;
            ++pos;
        }
        std::uint64_t value = 0;
        const std::size_t begin = pos;
        while (pos < text.size() && text[pos] >= '0' && text[pos] <= '9' && pos - begin < 6) {
            value = value * 10 + std::uint64_t(text[pos++] - '0');
        }
        if (pos == begin || value < 1 || value > limits::kMaxGridAxisCells) return std::nullopt;
        g.resolution[a] = static_cast<std::uint32_t>(value);
    }
    if (pos != text.size()) return std::nullopt;
    return g;
}

int run_render(const RenderArgs& args) {
    CommandTimes times;
    std::future<std::unique_ptr<Backend>> backend_made = make_backend_meanwhile(args, times.backend_seconds);
    PreparationProgress preparing(!args.quiet, stderr, isatty(fileno(stderr)) != 0);
    preparing.step("loading " + args.scene);
    Scene scene = load_scene(args.scene);
    times.load_seconds = seconds_since(times.start);
    prepare_scene(args, scene);
    const RenderTarget target = render_target(args);
    warn_ignored_options(args);

    Image reference;
    if (!args.reference.empty()) reference = read_reference(args.reference, scene.camera.width, scene.camera.height);
    live::LiveFeed feed;
    const std::unique_ptr<live::LiveServer> server = live::serve_if_asked(feed, args.serve, "the render as it converges");
    const std::unique_ptr<Backend> backend = backend_made.get();
    feed.set_renderer(backend->name(), backend->device_name());
    feed.set_display(scene.render.display);

    const std::string label = std::filesystem::path(args.scene).filename().string();
    const live::PassLabels labels{label, backend->name(), args.reference.empty() ? nullptr : &reference,
                                  args.time && !args.spp};
    auto last_checkpoint = std::chrono::steady_clock::now();
    RenderPlan plan = sample_plan(args, target.samples);
    plan.on_step = [&](const std::string& what) { preparing.step(what); };
    plan.after_pass = [&](const PassView& view) {
        if (!times.first_pass_seconds) times.first_pass_seconds = seconds_since(times.start);
        preparing.done();
        if (server) live::feed_pass(feed, view, labels);
        if (args.checkpoint && seconds_since(last_checkpoint) >= *args.checkpoint) {
            write_output(target.output, args, scene, backend->name(), view.total, target.samples, view.samples,
                         view.fingerprint, view.corners);
            last_checkpoint = std::chrono::steady_clock::now();
        }
        return !feed.stop_requested();
    };
    ProgressReporter progress("rendering", !args.quiet);
    RenderOutcome outcome = render_scene(scene, *backend, plan, [&](const ProgressiveStatus& status) {
        preparing.done();
        progress.update(status.fraction(), status.seconds_left, progress_detail(status));
    });
    progress.finish();
    write_output(target.output, args, scene, backend->name(), outcome.sums, target.samples,
                 outcome.stats.samples_per_pixel, outcome.fingerprint, outcome.corners, &outcome.image);

    RenderStats& s = outcome.stats;
    add_command_stats(s, times, scene);
    if (!args.stats_file.empty()) write_stats_file(args.stats_file, s);
    print_report(args, s, target, outcome.image, reference);
    if (server) finish_live_preview(feed, outcome, label, target.output);
    warn_about_render(s);
    check_render_complete(s, target.output);
    return 0;
}

// The variance of each pixel's mean that an image file carries: its "variance"
// layer (render --variance, or vkrt stack with its degrees of freedom), or, for a
// partial file, from its sums of squares.
struct CarriedVariance {
    Image image;
    double dof = std::numeric_limits<double>::infinity();
};

std::optional<CarriedVariance> carried_variance(const std::string& file) {
    if (std::optional<Image> layer = read_layer(file, "variance")) {
        CarriedVariance v{std::move(*layer)};
        std::string error;
        const std::unique_ptr<ImageFileReader> in = image_files().open(file, error);
        const std::string dof = in ? in->spec().string_or(kVarianceDofAttribute) : std::string();
        if (!dof.empty()) {
            std::size_t used = 0;
            try {
                v.dof = std::stod(dof, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != dof.size() || !(v.dof > 0.0)) {
                throw ImageError(fmt::format("{}: its {} attribute, '{}', is not a number above 0", file,
                                             kVarianceDofAttribute, dof));
            }
        }
        return v;
    }
    if (!app::is_exr(file)) return std::nullopt;
    try {
        read_partial_header(file);
    } catch (const ImageError&) {
        return std::nullopt;  // not a partial file
    }
    const PartialFile partial = read_partial(file);
    if (partial.corners) throw ImageError(fmt::format("{}: corner rays (the SPD's) have no variance", file));
    const ImageLayer v = variance_layer(partial.sums);
    CarriedVariance out{Image(partial.sums.width, partial.sums.height)};
    out.image.rgb = v.values;
    return out;
}

std::string describe_variance(const std::optional<CarriedVariance>& v) {
    if (!v) return "taken as exact";
    return v->dof < std::numeric_limits<double>::infinity() ? fmt::format("of {:g} degrees of freedom", v->dof)
                                                            : std::string("its own");
}

// compare --test: prints the verdict; true when it rejects.
bool run_z_test(const CompareArgs& args, const Image& a, const Image& b) {
    if (!args.p_values.empty() && !app::is_exr(args.p_values)) {
        throw ImageError(fmt::format("{}: --p-values writes an OpenEXR file: give a name ending in .exr", args.p_values));
    }
    const std::optional<CarriedVariance> var_a = carried_variance(args.a);
    if (!var_a) {
        throw ImageError(fmt::format("{}: --test needs the variance of A's pixel means: render it with --variance "
                                     "(.exr), give a partial file (render --samples), or a stack of independent "
                                     "images (vkrt stack)",
                                     args.a));
    }
    const std::optional<CarriedVariance> var_b = carried_variance(args.b);
    for (const auto& [name, v] : {std::pair{&args.a, &var_a}, std::pair{&args.b, &var_b}}) {
        if (*v && ((*v)->image.width != a.width || (*v)->image.height != a.height)) {
            throw ImageError(fmt::format("{}: its variance is {}x{}, the image {}x{}", *name, (*v)->image.width,
                                         (*v)->image.height, a.width, a.height));
        }
    }
    Image p_values;
    const ZTestResult t = z_test(a, PixelVariance{&var_a->image, var_a->dof}, b,
                                 var_b ? PixelVariance{&var_b->image, var_b->dof} : PixelVariance{}, args.alpha,
                                 args.p_values.empty() ? nullptr : &p_values);
    fmt::print("test      {} of {} pixel channels and the 3 image means tested (A's variance {}, B's {}), each at "
               "{:.3g} (alpha {:g}, Sidak)\n",
               t.tests, a.rgb.size(), describe_variance(var_a), describe_variance(var_b), t.level, t.alpha);
    fmt::print("          pixels: smallest p {:.3g}, z {:.3g} at pixel ({}, {}) channel {}\n", t.min_p, t.worst_z,
               t.worst_x, t.worst_y, "RGB"[t.worst_channel]);
    fmt::print("          image means A - B: R {:.4g} (z {:.3g}, p {:.3g}), G {:.4g} (z {:.3g}, p {:.3g}), B {:.4g} "
               "(z {:.3g}, p {:.3g})\n",
               t.means[0].difference, t.means[0].z, t.means[0].p, t.means[1].difference, t.means[1].z, t.means[1].p,
               t.means[2].difference, t.means[2].z, t.means[2].p);
    if (!args.p_values.empty()) {
        write_layered_exr(p_values, {}, args.p_values);
        fmt::print("          p-values in {}\n", args.p_values);
    }
    if (t.rejects()) {
        fmt::print("rejected: {} pixel channel{} and {} image mean{} differ by more than their noise explains\n",
                   t.rejected, t.rejected == 1 ? "" : "s", t.means_rejected, t.means_rejected == 1 ? "" : "s");
    } else {
        fmt::print("consistent: the difference is within the images' noise\n");
    }
    return t.rejects();
}

int run_compare(const CompareArgs& args) {
    const Image a = read_image(args.a);
    const Image b = read_image(args.b);
    if (a.width != b.width || a.height != b.height) {
        throw ImageError(fmt::format("{} is {}x{} but {} is {}x{}: only images of one size compare", args.a, a.width,
                                     a.height, args.b, b.width, b.height));
    }
    const ImageDiff d = compare_images(a, b, args.threshold);
    fmt::print("RMSE {:.6g}, max abs {:.6g}, PSNR {:.2f} dB, {} of {} pixels ({:.4f}%) differ by more than {:g}\n",
               d.rmse, d.max_abs, d.psnr, d.pixels_over, d.pixels, d.fraction_over() * 100.0, args.threshold);
    if (!args.metrics.empty()) {
        const ErrorMetrics e = error_metrics(a, b);
        for (const std::string& name : args.metrics) {
            const double value = name == "mae"    ? e.mae
                                 : name == "mse"  ? e.mse
                                 : name == "rmse" ? e.rmse
                                 : name == "relmse" ? e.relmse
                                                    : ssim(a, b);
            fmt::print("{} {:.6g}\n", name, value);
        }
    }
    if (!args.difference.empty()) {
        const double range = args.difference_range.value_or(largest_signed_difference(a, b));
        // Identical images: any range draws them white.
        write_difference_png(a, b, range > 0.0 ? range : 1.0, args.difference);
        fmt::print("difference A - B from -{0:.6g} (blue) to {0:.6g} (red) in {1}\n", range, args.difference);
    }
    bool over = args.test && run_z_test(args, a, b);
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

int run_devices(const DevicesArgs& args) {
    if (args.float_profile) {
        // Opened first, so an unwritable path is refused before any probing.
        std::ofstream json;
        if (!args.json.empty()) {
            json.open(args.json);
            if (!json) throw std::runtime_error(fmt::format("{}: cannot write the JSON file", args.json));
        }
        // The devices before any output: a bad --device is refused with nothing printed.
        const std::vector<DeviceProbeRun> runs = run_vulkan_float_probe(VulkanOptions{args.device, false});
        const std::vector<glm::vec4> cpu = probe::run_cpu_float_probe(probe::probe_cases());
        std::vector<probe::FloatProfile> columns{probe::summarize("cpu", cpu)};
        for (const DeviceProbeRun& run : runs) {
            columns.push_back(probe::summarize(run.device, run.results));
            probe::note_differences(columns.back(), run.results, cpu);
        }
        fmt::print("{}", probe::float_profile_table(columns));
        if (json.is_open()) {
            json << probe::float_profile_json(columns).dump(2) << "\n";
            if (!json) throw std::runtime_error(fmt::format("{}: cannot write the JSON file", args.json));
        }
        return 0;
    }
    if (args.limits) {
        fmt::print("{}", device_limits_report(args.profile));
        return 0;
    }
    const auto devices = list_vulkan_devices();
    for (const DeviceInfo& d : devices) {
        // Users are told to pick Mesa's CPU driver by its project name, which the
        // driver itself never prints.
        const bool lavapipe = d.driver.find("llvmpipe") != std::string::npos;
        fmt::print("{}: {} [{}] driver {}, Vulkan {}{}\n", d.index, d.name, d.type, d.driver, d.api_version,
                   lavapipe ? " (lavapipe: --device lavapipe)" : "");
    }
    if (devices.empty()) fmt::print("no Vulkan devices\n");
    return 0;
}

}  // namespace vkrt::cli
