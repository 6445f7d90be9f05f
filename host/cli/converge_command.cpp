// `vkrt converge`: its options; the work is in host/converge/.
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "cli/command.hpp"
#include "cli/options.hpp"
#include "converge/converge.hpp"
#include "live/live_server.hpp"
#include "scene/estimator_spec.hpp"
#include "scene/limits.hpp"

namespace vkrt::cli {

Command add_converge_command(CLI::App& program) {
    auto args = std::make_shared<converge::ConvergeArgs>();
    CLI::App* v = program.add_subcommand(
        "converge", "Measure error against a reference over render time, per backend and estimator (CSV and plot)");
    v->add_option("scene", args->scene, "Scene file (.json)")->required();
    v->add_option("--reference", args->reference,
                  "Reference image (.exr or .hdr, linear); default: render one with path+nee on the first backend and "
                  "save it beside the CSV as <csv name>_reference.exr");
    v->add_option("--reference-spp", args->reference_spp, "Samples per pixel of a reference rendered here")
        ->check(whole_number(1, limits::kMaxSpp))
        ->capture_default_str();
    v->add_option("--backend", args->backends, "Backend of a curve: vulkan or cpu; repeat for more (default: vulkan)")
        ->check(CLI::IsMember({"vulkan", "cpu"}))
        ->allow_extra_args(false);
    v->add_option("--estimator", args->estimators,
                  "Estimator of a curve: paper, path or path+nee, optionally :angles, :uniform or :cosine, then "
                  "optionally @sobol or @hash (e.g. path:uniform@hash); repeat for more (default: the scene's own)")
        ->check(accepted_by([](const std::string& text) { parse_estimator_spec(text); }, "SPEC"))
        ->allow_extra_args(false);
    v->add_option("--until", args->until, "Render each curve for this many seconds of passes")
        ->check(positive_seconds());
    v->add_option("--spp", args->spp,
                  fmt::format("Render each curve to this many samples per pixel (default without --until: {})",
                              converge::kDefaultConvergeSpp))
        ->check(whole_number(1, limits::kMaxSpp));
    v->add_option("--csv", args->csv, "CSV file of the measurements, one row per checkpoint")->required();
    v->add_option("--plot", args->plot, "Draw RMSE against seconds into this PNG (needs gnuplot)");
    v->add_option("--serve", args->serve,
                  "Serve a live preview at [ADDRESS:]PORT (address default 127.0.0.1, this machine only; port 0: "
                  "any free one): a web page drawing the curves as they are measured, with the current image and a "
                  "Stop button that ends the measurement after the current pass")
        ->check(accepted_by([](const std::string& text) { live::parse_endpoint(text); }, "[ADDRESS:]PORT"));
    add_image_size(v, args->width, args->height);
    add_seed(v, args->seed);
    add_device(v, args->device);
    add_threads(v, args->threads);
    add_validate(v, args->validate);
    add_quiet(v, args->quiet);
    return {v, [args] { return converge::run_converge(*args); }};
}

}  // namespace vkrt::cli
