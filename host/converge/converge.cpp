// vkrt converge: error against a reference over render time, at 1, 2, 4, ... samples
// per pixel, for each backend and estimator asked for, as CSV rows and a plot.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "app/output_paths.hpp"
#include "converge/converge.hpp"
#include "converge/plot.hpp"
#include "app/progress.hpp"
#include "gpu/vulkan_backend.hpp"
#include "image/error_metrics.hpp"
#include "image/image.hpp"
#include "live/live_server.hpp"
#include "live/pass_feed.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/partial_file.hpp"
#include "render/progressive.hpp"
#include "render/render.hpp"
#include "scene/estimator_spec.hpp"
#include "scene/limits.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"

namespace vkrt::converge {
namespace {

// The reference's random numbers must not be the curves': with the same seed its
// first samples would be theirs, and the error of the first checkpoints would
// come out too small. A fixed other seed keeps the run reproducible.
constexpr std::uint32_t kReferenceSeedXor = 0x9e3779b9u;

struct Curve {
    std::string backend;
    std::string label;  // estimator
    std::optional<EstimatorSpec> spec;
};

struct Row {
    std::uint32_t spp;
    double seconds;
    ErrorMetrics error;
};

std::unique_ptr<Backend> make_named_backend(const std::string& name, const ConvergeArgs& args) {
    if (name == "cpu") return make_cpu_backend(args.threads);
    return make_vulkan_backend(VulkanOptions{args.device, args.validate});
}

Scene load_with_overrides(const ConvergeArgs& args) {
    Scene scene = load_scene(args.scene);
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "warning: {}\n", warning);
    if (args.width) scene.camera.width = *args.width;
    if (args.height) scene.camera.height = *args.height;
    if (args.seed) scene.render.seed = *args.seed;
    if (const std::string problem =
            limits::image_size_problem(scene.camera.width, scene.camera.height, scene.render.corners);
        !problem.empty()) {
        throw SceneError("--width/--height: " + problem);
    }
    return scene;
}

std::vector<Curve> plan_curves(const ConvergeArgs& args, const Scene& scene) {
    std::vector<std::string> backends = args.backends.empty() ? std::vector<std::string>{"vulkan"} : args.backends;
    std::set<std::string> seen;
    for (const std::string& b : backends) {
        if (!seen.insert(b).second) throw std::runtime_error(fmt::format("--backend {} is given twice", b));
    }
    std::vector<std::optional<EstimatorSpec>> specs;
    std::set<std::string> labels;
    for (const std::string& text : args.estimators) {
        const EstimatorSpec spec = parse_estimator_spec(text);  // checked by the parser
        if (!labels.insert(spec.label()).second) {
            throw std::runtime_error(fmt::format("--estimator {} is given twice (as {})", text, spec.label()));
        }
        specs.push_back(spec);
    }
    if (specs.empty()) specs.push_back(std::nullopt);
    std::vector<Curve> curves;
    const std::string own = scene.render.mode == RenderMode::Local ? "local" : estimator_spec_of(scene.render).label();
    for (const std::string& b : backends) {
        for (const auto& spec : specs) curves.push_back({b, spec ? spec->label() : own, spec});
    }
    return curves;
}

// Renders the reference on `backend`: path tracing with next-event estimation at
// reference_spp, another seed; saved as a partial file, so more samples can be
// merged into it later.
Image render_reference(const ConvergeArgs& args, Scene scene, Backend& backend, const std::filesystem::path& file,
                       live::LiveFeed& feed) {
    EstimatorSpec{Estimator::Path, Hemisphere::Cosine, true}.apply(scene.render);
    scene.render.seed ^= kReferenceSeedXor;
    scene.render.squares = true;  // a partial file, as `render --samples` writes one (and merges with it)
    fmt::print(stderr,
               "converge: no --reference given: rendering one on {} (path+nee:cosine, {} spp, seed {}) to {}; pass "
               "it as --reference next time\n",
               backend.name(), args.reference_spp, scene.render.seed, file.string());
    RenderPlan plan;
    plan.samples = args.reference_spp;
    feed.set_renderer(backend.name(), backend.device_name());
    plan.after_pass = [&](const PassView& view) {
        live::feed_pass(feed, view, {"reference", "", nullptr});
        return true;  // the curves need the whole reference
    };
    ProgressReporter progress("reference", !args.quiet);
    const RenderOutcome outcome = render_scene(scene, backend, plan, [&](const ProgressiveStatus& s) {
        progress.update(s.fraction(), s.seconds_left, fmt::format("{} spp", s.whole_samples));
    });
    progress.finish();
    write_partial(PartialFile{outcome.sums, {SampleRange{0, args.reference_spp}},
                              std::filesystem::path(args.scene).filename().string(), scene.render.seed,
                              outcome.fingerprint, backend.name(), outcome.corners},
                  file);
    return outcome.image;
}

// One curve: progressive passes that stop at every checkpoint (1, 2, 4, ... and
// the last sample), where the image is compared with the reference. The seconds
// are the passes' own, so the comparisons do not count as render time.
std::vector<Row> run_curve(const ConvergeArgs& args, Scene scene, const Curve& curve, Backend& backend,
                           const Image& reference, std::uint64_t& truncated, live::LiveFeed& feed) {
    if (curve.spec) curve.spec->apply(scene.render);
    const FlatScene gpu = flatten_scene(scene, backend.accel_policy());
    const std::unique_ptr<RenderSession> session = backend.begin(gpu);
    const std::uint32_t limit = args.spp.value_or(args.until ? limits::kMaxSpp : kDefaultConvergeSpp);
    ProgressiveRender render(*session, {SampleRange{0, limit}, args.until});
    ProgressReporter progress(curve.backend + " " + curve.label, !args.quiet);
    const ProgressiveCallback report = [&](const ProgressiveStatus& s) {
        progress.update(s.fraction(), s.seconds_left,
                        fmt::format("{} spp, {:.3g} spp/s", s.whole_samples, s.samples_per_second()));
    };
    std::vector<Row> rows;
    const std::string name = curve.backend + "/" + curve.label;
    auto record = [&] {
        rows.push_back({render.samples_done(), render.seconds(),
                        error_metrics(resolve_image(render.total(), gpu.corners), reference)});
        feed.add_error_point(name, rows.back().seconds, rows.back().error.rmse);
    };
    // Where the render stopped between checkpoints (time, or the Stop button): a row too.
    auto record_last = [&] {
        if (render.samples_done() > 0 && (rows.empty() || rows.back().spp != render.samples_done())) record();
    };
    feed.set_renderer(backend.name(), backend.device_name());
    for (std::uint32_t checkpoint = 1;;) {
        const bool rendered = render.next_pass(checkpoint, report);
        if (rendered) {
            live::feed_pass(feed,
                            PassView{render.total(), gpu.corners, 0, render.samples_done(), limit, render.passes(),
                                     render.elapsed(), render.seconds_left(), 0},
                            {name, name, nullptr});
        }
        if (feed.stop_requested()) {
            record_last();
            break;
        }
        if (render.samples_done() == checkpoint) {
            record();
            if (checkpoint == limit) break;
            checkpoint = std::min(checkpoint * 2, limit);
        } else if (!rendered) {
            record_last();
            break;
        }
    }
    progress.finish();
    for (const kernel::Counters& c : render.total().counters) truncated += c.work[kernel::WORK_TRUNCATED];
    if (!args.quiet) {
        fmt::print("curve     {} {}: {} checkpoints, 1 to {} spp in {:.3f} s of passes (set-up {:.3f} s), RMSE {:.4g} "
                   "to {:.4g}\n",
                   curve.backend, curve.label, rows.size(), rows.back().spp, rows.back().seconds,
                   session->setup_seconds(), rows.front().error.rmse, rows.back().error.rmse);
    }
    return rows;
}

}  // namespace

int run_converge(const ConvergeArgs& args) {
    const Scene scene = load_with_overrides(args);
    const std::vector<Curve> curves = plan_curves(args, scene);
    if (!args.estimators.empty() && scene.render.mode == RenderMode::Local) {
        fmt::print(stderr,
                   "warning: {} renders in local mode, where no estimator is used: the --estimator curves differ "
                   "by name only (set \"mode\": \"global\" in its render settings)\n",
                   args.scene);
    }

    // Every output and the plotting tool are checked before the first sample.
    app::check_writable_file(args.csv, "CSV file");
    std::string gnuplot;
    std::filesystem::path script;
    if (!args.plot.empty()) {
        app::check_writable_image(args.plot);
        if (std::filesystem::path(args.plot).extension() != ".png") {
            throw std::runtime_error(fmt::format("--plot {}: the plot is drawn as PNG: give a name ending in .png",
                                                 args.plot));
        }
        gnuplot = find_gnuplot();
        script = plot_script();
    }
    const std::filesystem::path csv_path(args.csv);
    const std::filesystem::path reference_file =
        args.reference.empty() ? csv_path.parent_path() / (csv_path.stem().string() + "_reference.exr")
                               : std::filesystem::path(args.reference);
    Image reference;
    if (!args.reference.empty()) reference = read_reference(args.reference, scene.camera.width, scene.camera.height);

    live::LiveFeed feed;
    const std::unique_ptr<live::LiveServer> server = live::serve_if_asked(feed, args.serve, "the curves as they are measured");

    std::vector<std::unique_ptr<Backend>> backends;
    std::vector<std::string> names;
    for (const Curve& c : curves) {
        if (std::find(names.begin(), names.end(), c.backend) != names.end()) continue;
        names.push_back(c.backend);
        backends.push_back(make_named_backend(c.backend, args));
    }
    if (args.reference.empty()) reference = render_reference(args, scene, *backends.front(), reference_file, feed);
    if (!args.quiet) {
        fmt::print("reference {} ({})\n", reference_file.string(),
                   args.reference.empty() ? fmt::format("rendered here, {} spp", args.reference_spp) : "given");
    }

    std::ofstream csv(args.csv);
    csv << "backend,estimator,spp,seconds,rmse,relmse,mean,mean_diff\n";
    std::uint64_t truncated = 0;
    bool any_error = false;
    std::vector<std::string> drawn;
    for (const Curve& curve : curves) {
        if (feed.stop_requested()) {
            fmt::print(stderr, "warning: stopped from the live preview: curve {}/{} not measured\n", curve.backend,
                       curve.label);
            continue;
        }
        Backend& backend = *backends[std::size_t(std::find(names.begin(), names.end(), curve.backend) - names.begin())];
        for (const Row& r : run_curve(args, scene, curve, backend, reference, truncated, feed)) {
            csv << fmt::format("{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", curve.backend, curve.label, r.spp,
                               r.seconds, r.error.rmse, r.error.relmse, r.error.mean, r.error.mean_diff);
            any_error = any_error || r.error.rmse > 0.0;
        }
        drawn.push_back(curve.backend + "/" + curve.label);
    }
    csv.close();
    if (!csv) throw std::runtime_error(fmt::format("{}: cannot write the CSV file", args.csv));
    if (!args.quiet) fmt::print("wrote     {}\n", args.csv);

    if (!args.plot.empty()) {
        if (any_error) {
            plot_convergence(gnuplot, script, args.csv, args.plot, drawn);
            if (!args.quiet) fmt::print("wrote     {}\n", args.plot);
        } else {
            fmt::print(stderr,
                       "warning: every RMSE is 0 (the scene has no randomness, so each sample equals the reference): "
                       "no plot drawn, a log scale cannot show it\n");
        }
    }
    if (server) {
        feed.finish(args.csv);
        feed.wait_until_seen(2.0);
    }
    std::uint32_t messages = 0;
    for (const auto& b : backends) messages += b->validation_messages();
    if (messages > 0) {
        throw std::runtime_error(fmt::format("the Vulkan validation layer reported {} messages (above)", messages));
    }
    if (truncated > 0) {
        throw std::runtime_error(fmt::format(
            "{} samples ran out of the per-invocation loop budget and were left out: the errors in {} are not "
            "those of complete images",
            truncated, args.csv));
    }
    return 0;
}

}  // namespace vkrt::converge
