// `vkrt bench`: its options; the work is in host/bench/.
#include <memory>
#include <string>

#include "bench/bench.hpp"
#include "cli/command.hpp"
#include "cli/options.hpp"
#include "scene/limits.hpp"

namespace vkrt::cli {
namespace {

// The command as typed, for the header of the benchmark's table.
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

Command add_bench_command(CLI::App& program, int argc, char** argv) {
    auto args = std::make_shared<bench::BenchArgs>();
    args->command_line = command_line(argc, argv);
    CLI::App* b =
        program.add_subcommand("bench", "Measure rays per second: grid against brute force, vulkan against cpu");
    CLI::Option* scene = b->add_option("--scene", args->scenes,
                                       "Scene file to measure; repeat for more (default: the list in docs/bench.md, "
                                       "from the source tree)")
                             ->allow_extra_args(false);
    CLI::Option* width = b->add_option("--width", args->width, "Image width")
                             ->check(whole_number(1, limits::kMaxImageSide))
                             ->capture_default_str();
    CLI::Option* height = b->add_option("--height", args->height, "Image height")
                              ->check(whole_number(1, limits::kMaxImageSide))
                              ->capture_default_str();
    b->add_option("--runs", args->runs, "Runs per measurement; the median is reported")
        ->check(whole_number(1, 1000))
        ->capture_default_str();
    b->add_option("--backend", args->backend, "Backends to measure: vulkan, cpu or both")
        ->check(CLI::IsMember({"vulkan", "cpu", "both"}))
        ->capture_default_str();
    add_device(b, args->device);
    b->add_option("--csv", args->csv, "Also write the measurements to this CSV file");
    CLI::Option* sweep = b->add_flag("--sweep", args->sweep,
                                     "Measure 1k, 10k, 100k and 1M random spheres: cost against primitive count");
    CLI::Option* threshold = b->add_flag("--threshold", args->threshold,
                                         "Measure 1 to 256 random spheres, grid on and off: where the grid starts to win");
    CLI::Option* spd = b->add_flag("--spd", args->spd,
                                   "Measure the SPD scenes under the SPD rules: ray counts against the published "
                                   "ones, preprocessing and ray-tracing times");
    b->add_option("--spd-dir", args->spd_dir,
                  "Where --spd finds the SPD .nff (or .nff.gz) files; default: the source tree's scenes/spd")
        ->needs(spd);
    // The SPD rules fix the image (the file's resolution) and the scene list, and the
    // SPD table has its own columns: none of these mean anything with --spd.
    spd->excludes(scene)->excludes(width)->excludes(height)->excludes(sweep)->excludes(threshold);
    add_quiet(b, args->quiet, "No progress lines on standard error");
    return {b, [args] { return bench::run_bench(*args); }};
}

}  // namespace vkrt::cli
