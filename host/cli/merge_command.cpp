// `vkrt merge` and `vkrt compare`: their options; the work is run_merge
// (cli/merge.cpp) and run_compare (cli/commands.cpp).
#include <memory>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "render/sample_ranges.hpp"
#include "scene/limits.hpp"

namespace vkrt::cli {

Command add_merge_command(CLI::App& program) {
    auto args = std::make_shared<MergeArgs>();
    CLI::App* m = program.add_subcommand("merge", "Add up partial files of disjoint sample ranges into one image");
    m->add_option("partials", args->partials, "Partial files (.exr) written by vkrt render --samples or vkrt merge");
    CLI::Option* output = m->add_option(
        "-o,--output", args->output, "Output image; .exr writes a partial file again (mergeable), other formats an image");
    m->add_option("--samples", args->samples,
                  "The samples A to B-1 the partials must cover, all of them (without it: from their first sample to "
                  "their last); samples left out are an error, named")
        ->check(accepted_by([](const std::string& text) { parse_sample_range(text, limits::kMaxSpp); }, "A:B"));
    m->add_flag("--allow-gaps", args->allow_gaps,
                "Merge even when samples are left out: each pixel averages the samples there are");
    CLI::Option* missing = m->add_flag(
        "--missing", args->missing,
        "Print the ranges of --samples that no readable partial covers, one A:B a line, and write nothing: what is "
        "left to render. Damaged or unreadable partials count as missing");
    m->add_option("--tasks", args->tasks, "With --missing: cut the missing samples into about this many ranges")
        ->check(CLI::Range(1u, 65536u))
        ->needs(missing);
    missing->excludes(output);
    add_display(m, args->display, " (default: none and 0)");
    add_quiet(m, args->quiet);
    return {m, [args] { return run_merge(*args); }};
}

Command add_compare_command(CLI::App& program) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* c = program.add_subcommand("compare", "Compare two images; exit 1 when over a given bound");
    c->add_option("a", args->a, "First image")->required();
    c->add_option("b", args->b, "Second image")->required();
    c->add_option("--max-rmse", args->max_rmse, "Fail when the RMSE is above this")->check(non_negative());
    c->add_option("--max-abs", args->max_abs, "Fail when the largest channel difference is above this")
        ->check(non_negative());
    c->add_option("--threshold", args->threshold, "Per-channel difference counted as a differing pixel")
        ->check(non_negative())
        ->capture_default_str();
    c->add_option("--metric", args->metrics,
                  "Also print these, comma-separated: mae, mse, rmse, relmse (B the reference), ssim")
        ->delimiter(',')
        ->check(CLI::IsMember(std::vector<std::string>(kCompareMetrics.begin(), kCompareMetrics.end())));
    CLI::Option* difference = c->add_option(
        "--difference", args->difference,
        "Write the signed difference A - B of each pixel (its channels' mean) to this .png: blue below, red above, "
        "white equal");
    c->add_option("--difference-range", args->difference_range,
                  "The difference drawn at the colour map's ends (default: the largest, printed)")
        ->check(CLI::PositiveNumber)
        ->needs(difference);
    CLI::Option* test = c->add_flag(
        "--test", args->test,
        "Test whether A - B is noise: A must carry the variance of its pixel means (render --variance, a partial "
        "file, or vkrt stack), B may (else it counts as exact). Per pixel channel and per image mean a Z-score (a "
        "t-score where a variance comes from a stack), Sidak-corrected; exit 1 when it rejects");
    c->add_option("--alpha", args->alpha, "--test's chance of rejecting two images that agree")
        ->check(CLI::Range(1e-12, 0.5))
        ->capture_default_str()
        ->needs(test);
    c->add_option("--p-values", args->p_values, "Write each pixel channel's p-value of --test to this .exr")
        ->needs(test);
    // compare keeps 1 for "over the bound", so a script can tell the two apart.
    return {c, [args] { return run_compare(*args); }, 2};
}

}  // namespace vkrt::cli
