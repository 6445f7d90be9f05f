// vkrt: command-line parsing only; the work is in cli/commands.cpp.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "cli/bench.hpp"
#include "cli/commands.hpp"
#include "render/sample_ranges.hpp"
#include "scene/estimator_spec.hpp"
#include "scene/limits.hpp"

namespace {

// CLI11's Range validator runs before conversion and so answers "abc" with "not in
// range"; these say what was wrong.
CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            std::size_t used = 0;
            unsigned long long value = 0;
            try {
                value = std::stoull(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != text.size() || text.empty() || text[0] == '-' || value < lo || value > hi) {
                return fmt::format("expected a whole number from {} to {}, got '{}'", lo, hi, text);
            }
            return {};
        },
        fmt::format("{}..{}", lo, hi));
}

CLI::Validator non_negative() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::size_t used = 0;
            double value = -1.0;
            try {
                value = std::stod(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != text.size() || !(value >= 0.0)) {
                return fmt::format("expected a number >= 0, got '{}'", text);
            }
            return {};
        },
        ">= 0");
}

// A time budget: finite and above zero (a budget of 0 could render nothing).
CLI::Validator positive_seconds() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::size_t used = 0;
            double value = 0.0;
            try {
                value = std::stod(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != text.size() || !(value > 0.0) || !std::isfinite(value)) {
                return fmt::format("expected a number of seconds above 0, got '{}'", text);
            }
            return {};
        },
        "SECONDS > 0");
}

// The command as typed, for the header of `vkrt bench`'s table.
std::string command_line(int argc, char** argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) {
        const std::string word = argv[i];
        if (i > 0) line += ' ';
        line += word.find_first_of(" \t'\"") == std::string::npos ? word : "'" + word + "'";
    }
    return line;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace vkrt;
    CLI::App app{"vkrt: a ray tracer whose renderer is a Vulkan compute shader, with a C++ reference"};
    app.set_version_flag("--version", "vkrt " VKRT_VERSION);
    app.require_subcommand(1);

    cli::RenderArgs render;
    CLI::App* r = app.add_subcommand("render", "Render a scene file to an image");
    r->add_option("scene", render.scene, "Scene file (.json)")->required();
    r->add_option("-o,--output", render.output,
                  "Output image; the extension picks the format (.png .ppm: 8-bit sRGB; .exr .hdr: linear float). "
                  "Default: <scene name>.png");
    r->add_option("--backend", render.backend, "Renderer: vulkan (compute shader) or cpu (C++ reference)")
        ->check(CLI::IsMember({"vulkan", "cpu"}))
        ->capture_default_str();
    r->add_option("--device", render.device, "Vulkan device: index or name from `vkrt devices` (e.g. lavapipe)");
    r->add_option("--width", render.width, "Image width, overrides the scene")
        ->check(whole_number(1, limits::kMaxImageSide));
    r->add_option("--height", render.height, "Image height, overrides the scene")
        ->check(whole_number(1, limits::kMaxImageSide));
    r->add_option("--spp", render.spp, "Samples per pixel (default: the scene's, else aa*aa)")
        ->check(whole_number(1, limits::kMaxSpp));
    r->add_option("--time", render.time,
                  "Render progressive passes for this many seconds, then stop (with --spp: whichever comes first)")
        ->check(positive_seconds());
    CLI::Option* samples_opt =
        r->add_option("--samples", render.samples,
                      "Render only the samples A to B-1 of every pixel, to a partial file (.exr) that vkrt merge adds "
                      "up with others (default output: <scene name>_A-B.exr)")
            ->check(CLI::Validator(
                [](const std::string& text) {
                    try {
                        parse_sample_range(text, limits::kMaxSpp);
                    } catch (const std::invalid_argument& e) {
                        return std::string(e.what());
                    }
                    return std::string();
                },
                "A:B"));
    r->add_option("--seed", render.seed, "Random seed, overrides the scene")
        ->check(whole_number(0, 0xffffffffu));
    r->add_option("--grid", render.grid,
                  "Uniform grid: auto (when the scene has enough primitives for it to pay), on, off, or a "
                  "resolution NXxNYxNZ in cells (e.g. 46x46x3); overrides the scene")
        ->check(CLI::Validator(
            [](const std::string& text) {
                return cli::parse_grid_option(text)
                           ? std::string()
                           : fmt::format("expected auto, on, off or NXxNYxNZ (each 1 to {}), got '{}'",
                                         limits::kMaxGridAxisCells, text);
            },
            "auto|on|off|NXxNYxNZ"));
    r->add_option("--threads", render.threads, "CPU threads for the cpu backend (default: all)")
        ->check(whole_number(0, 1024));
    r->add_option("--stats", render.stats_file, "Write render statistics as JSON to this file");
    r->add_flag("--validate", render.validate,
                "Enable the Vulkan validation layer; any message makes the render fail");
    r->add_flag("-q,--quiet", render.quiet, "Print nothing but warnings and errors");
    // A partial file is a fixed range of samples: a count or a time budget would
    // contradict it.
    samples_opt->excludes("--spp")->excludes("--time");

    cli::MergeArgs merge;
    CLI::App* m = app.add_subcommand("merge", "Add up partial files of disjoint sample ranges into one image");
    m->add_option("partials", merge.partials, "Partial files (.exr) written by vkrt render --samples or vkrt merge")
        ->required();
    m->add_option("-o,--output", merge.output,
                  "Output image; .exr writes a partial file again (mergeable), other formats an image")
        ->required();
    m->add_flag("-q,--quiet", merge.quiet, "Print nothing but warnings and errors");

    cli::ConvergeArgs converge;
    CLI::App* v = app.add_subcommand(
        "converge", "Measure error against a reference over render time, per backend and estimator (CSV and plot)");
    v->add_option("scene", converge.scene, "Scene file (.json)")->required();
    v->add_option("--reference", converge.reference,
                  "Reference image (.exr or .hdr, linear); default: render one with path+nee on the first backend and "
                  "save it beside the CSV as <csv name>_reference.exr");
    v->add_option("--reference-spp", converge.reference_spp, "Samples per pixel of a reference rendered here")
        ->check(whole_number(1, limits::kMaxSpp))
        ->capture_default_str();
    v->add_option("--backend", converge.backends, "Backend of a curve: vulkan or cpu; repeat for more (default: vulkan)")
        ->check(CLI::IsMember({"vulkan", "cpu"}))
        ->allow_extra_args(false);
    v->add_option("--estimator", converge.estimators,
                  "Estimator of a curve: paper, path or path+nee, optionally :angles, :uniform or :cosine; repeat for "
                  "more (default: the scene's own)")
        ->check(CLI::Validator(
            [](const std::string& text) {
                try {
                    parse_estimator_spec(text);
                } catch (const std::invalid_argument& e) {
                    return std::string(e.what());
                }
                return std::string();
            },
            "SPEC"))
        ->allow_extra_args(false);
    v->add_option("--until", converge.until, "Render each curve for this many seconds of passes")
        ->check(positive_seconds());
    v->add_option("--spp", converge.spp,
                  fmt::format("Render each curve to this many samples per pixel (default without --until: {})",
                              cli::kDefaultConvergeSpp))
        ->check(whole_number(1, limits::kMaxSpp));
    v->add_option("--csv", converge.csv, "CSV file of the measurements, one row per checkpoint")->required();
    v->add_option("--plot", converge.plot, "Draw RMSE against seconds into this PNG (needs gnuplot)");
    v->add_option("--width", converge.width, "Image width, overrides the scene")
        ->check(whole_number(1, limits::kMaxImageSide));
    v->add_option("--height", converge.height, "Image height, overrides the scene")
        ->check(whole_number(1, limits::kMaxImageSide));
    v->add_option("--seed", converge.seed, "Random seed, overrides the scene")->check(whole_number(0, 0xffffffffu));
    v->add_option("--device", converge.device, "Vulkan device: index or name from `vkrt devices` (e.g. lavapipe)");
    v->add_option("--threads", converge.threads, "CPU threads for the cpu backend (default: all)")
        ->check(whole_number(0, 1024));
    v->add_flag("--validate", converge.validate,
                "Enable the Vulkan validation layer; any message makes the command fail");
    v->add_flag("-q,--quiet", converge.quiet, "Print nothing but warnings and errors");

    cli::CompareArgs compare;
    CLI::App* c = app.add_subcommand("compare", "Compare two images; exit 1 when over a given bound");
    c->add_option("a", compare.a, "First image")->required();
    c->add_option("b", compare.b, "Second image")->required();
    c->add_option("--max-rmse", compare.max_rmse, "Fail when the RMSE is above this")
        ->check(non_negative());
    c->add_option("--max-abs", compare.max_abs, "Fail when the largest channel difference is above this")
        ->check(non_negative());
    c->add_option("--threshold", compare.threshold, "Per-channel difference counted as a differing pixel")
        ->check(non_negative())
        ->capture_default_str();

    cli::BenchArgs bench;
    bench.command_line = command_line(argc, argv);
    CLI::App* b = app.add_subcommand("bench", "Measure rays per second: grid against brute force, vulkan against cpu");
    CLI::Option* scene_opt =
        b->add_option("--scene", bench.scenes,
                      "Scene file to measure; repeat for more (default: the list in docs/bench.md, relative to the "
                      "repo root)")
            ->allow_extra_args(false);
    CLI::Option* width_opt = b->add_option("--width", bench.width, "Image width")
        ->check(whole_number(1, limits::kMaxImageSide))
        ->capture_default_str();
    CLI::Option* height_opt = b->add_option("--height", bench.height, "Image height")
        ->check(whole_number(1, limits::kMaxImageSide))
        ->capture_default_str();
    b->add_option("--runs", bench.runs, "Runs per measurement; the median is reported")
        ->check(whole_number(1, 1000))
        ->capture_default_str();
    b->add_option("--backend", bench.backend, "Backends to measure: vulkan, cpu or both")
        ->check(CLI::IsMember({"vulkan", "cpu", "both"}))
        ->capture_default_str();
    b->add_option("--device", bench.device, "Vulkan device: index or name from `vkrt devices` (e.g. lavapipe)");
    b->add_option("--csv", bench.csv, "Also write the measurements to this CSV file");
    CLI::Option* sweep_opt = b->add_flag("--sweep", bench.sweep,
                                         "Measure 1k, 10k, 100k and 1M random spheres: cost against primitive count");
    CLI::Option* threshold_opt =
        b->add_flag("--threshold", bench.threshold,
                    "Measure 1 to 256 random spheres, grid on and off: where the grid starts to win");
    CLI::Option* spd = b->add_flag("--spd", bench.spd,
                                   "Measure the SPD scenes under the SPD rules: ray counts against the published "
                                   "ones, preprocessing and ray-tracing times");
    b->add_option("--spd-dir", bench.spd_dir,
                  "Where --spd finds the SPD .nff (or .nff.gz) files; default: the source tree's scenes/spd")
        ->needs(spd);
    // The SPD rules fix the image (the file's resolution) and the scene list, and the
    // SPD table has its own columns: none of these mean anything with --spd.
    spd->excludes(scene_opt)->excludes(width_opt)->excludes(height_opt)->excludes(sweep_opt)->excludes(threshold_opt);
    b->add_flag("-q,--quiet", bench.quiet, "No progress lines on standard error");

    cli::DevicesArgs devices;
    CLI::App* d = app.add_subcommand("devices", "List the Vulkan devices");
    CLI::Option* float_profile =
        d->add_flag("--float-profile", devices.float_profile,
                    "Probe each device's float arithmetic against the CPU's and print a table (docs/numerics.md)");
    d->add_option("--device", devices.device, "With --float-profile: only this device, index or name (e.g. lavapipe)")
        ->needs(float_profile);
    d->add_option("--json", devices.json, "With --float-profile: also write the profile to this JSON file")
        ->needs(float_profile);

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line and status 1, like every other mistake (docs/cli.md).
        if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
            fmt::print(stderr, "error: unknown command '{}' (expected render, merge, converge, compare, bench or devices)\n",
                       argv[1]);
            return 1;
        }
        fmt::print(stderr, "error: {} (see vkrt {}--help)\n", e.what(),
                   r->parsed()   ? "render "
                   : m->parsed() ? "merge "
                   : v->parsed() ? "converge "
                   : c->parsed() ? "compare "
                   : b->parsed() ? "bench "
                   : d->parsed() ? "devices "
                                 : "");
        return 1;
    }
    try {
        if (r->parsed()) return cli::run_render(render);
        if (m->parsed()) return cli::run_merge(merge);
        if (v->parsed()) return cli::run_converge(converge);
        if (c->parsed()) return cli::run_compare(compare);
        if (b->parsed()) return cli::run_bench(bench);
        return cli::run_devices(devices);
    } catch (const std::exception& e) {
        fmt::print(stderr, "error: {}\n", e.what());
        // compare keeps 1 for "over the bound", so a script can tell the two apart.
        return c->parsed() ? 2 : 1;
    }
}
