// `vkrt stack`: independent images of one scene (another renderer's, with other
// seeds) made one image with the variance of its pixel means (image/stack.hpp), for
// vkrt compare --test.
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/output_paths.hpp"
#include "cli/command.hpp"
#include "cli/options.hpp"
#include "image/image.hpp"
#include "image/stack.hpp"

namespace vkrt::cli {

namespace {

struct StackArgs {
    std::vector<std::string> images;
    std::string output;
    bool quiet = false;
};

int run_stack(const StackArgs& args) {
    if (!app::is_exr(args.output)) {
        throw ImageError(fmt::format("{}: the stack is written with its variance layer into an OpenEXR file: give "
                                     "-o a name ending in .exr",
                                     args.output));
    }
    app::check_writable_image(args.output);
    std::vector<Image> images;
    for (const std::string& file : args.images) images.push_back(read_image(file));
    const StackedImage s = stack_images(images);
    app::write_atomically(args.output, [&](const std::filesystem::path& file) {
        write_layered_exr(s.mean, {ImageLayer{"variance", {"R", "G", "B"}, s.variance.rgb}}, file,
                          {{kVarianceDofAttribute, fmt::format("{:g}", s.dof)}});
    });
    if (!args.quiet) {
        fmt::print("stacked {} images of {}x{} into {}: their mean, and the variance of that mean (layer variance, "
                   "{:g} degrees of freedom)\n",
                   images.size(), s.mean.width, s.mean.height, args.output, s.dof);
    }
    return 0;
}

}  // namespace

Command add_stack_command(CLI::App& program) {
    auto args = std::make_shared<StackArgs>();
    CLI::App* s = program.add_subcommand(
        "stack", "Average independent images of one scene (other seeds) into one image with the variance of its "
                 "pixel means, for compare --test");
    s->add_option("images", args->images,
                  "Two or more images of one size, each an independent estimate of the same image (linear: .exr, "
                  ".hdr, .pfm)")
        ->required();
    s->add_option("-o,--output", args->output, "Output (.exr): the mean, and its variance as the layer variance")
        ->required();
    add_quiet(s, args->quiet);
    return {s, [args] { return run_stack(*args); }};
}

}  // namespace vkrt::cli
