// `vkrt render`: its options; the work is run_render (cli/commands.cpp).
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "cli/command.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "live/live_server.hpp"
#include "render/sample_ranges.hpp"
#include "scene/limits.hpp"

namespace vkrt::cli {

Command add_render_command(CLI::App& program) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* r = program.add_subcommand("render", "Render a scene file to an image");
    r->add_option("scene", args->scene, "Scene file (.json, .nff, either optionally gzipped as .gz; .gltf, .glb)")->required();
    r->add_option("-o,--output", args->output,
                  "Output image; the extension picks the format (.png .ppm: 8-bit sRGB; .exr .hdr .pfm: linear float). "
                  "Default: <scene name>.png");
    r->add_option("--backend", args->backend, "Renderer: vulkan (compute shader) or cpu (C++ reference)")
        ->check(CLI::IsMember({"vulkan", "cpu"}))
        ->capture_default_str();
    add_device(r, args->device);
    add_image_size(r, args->width, args->height);
    r->add_option("--spp", args->spp, "Samples per pixel (default: the scene's, else aa*aa)")
        ->check(whole_number(1, limits::kMaxSpp));
    r->add_option("--time", args->time,
                  "Render progressive passes for this many seconds, then stop (with --spp: whichever comes first)")
        ->check(positive_seconds());
    CLI::Option* samples =
        r->add_option("--samples", args->samples,
                      "Render only the samples A to B-1 of every pixel, to a partial file (.exr) that vkrt merge adds "
                      "up with others (default output: <scene name>_A-B.exr)")
            ->check(accepted_by([](const std::string& text) { parse_sample_range(text, limits::kMaxSpp); }, "A:B"));
    add_seed(r, args->seed);
    r->add_option("--sampler", args->sampler,
                  "Random numbers: sobol (Owen-scrambled Sobol points) or hash (independent); overrides the scene")
        ->check(CLI::IsMember({"sobol", "hash"}));
    r->add_option("--bounces", args->bounces,
                  "Global mode: scattering events after the first hit (render.max_bounces); overrides the scene")
        ->check(whole_number(0, limits::kMaxBounces));
    CLI::Option* background_option = r->add_option("--background", args->background,
                  "Radiance of rays that hit nothing, one number or R,G,B (render.background; in global mode the "
                  "uniform sky that lights the scene); overrides the scene")
        ->check(accepted_by([](const std::string& text) { parse_colour(text); }, "V|R,G,B"));
    r->add_option("--environment", args->environment,
                  "Image around the scene (equirectangular; .exr or .hdr for light, any texture format), seen by "
                  "rays that leave the scene and, in global mode, lighting it (render.background's image); "
                  "overrides the scene")
        ->excludes(background_option);
    r->add_option("--environment-intensity", args->environment_intensity,
                  "Factor on the environment image's values (render.background.intensity); overrides the scene")
        ->check(CLI::Range(0.0, 1e6));
    r->add_option("--environment-rotation", args->environment_rotation,
                  "Degrees the environment image turns about its up axis, right-handed (render.background.rotation); "
                  "overrides the scene")
        ->check(CLI::Range(-1e6, 1e6));
    add_display(r, args->display, "; overrides the scene");
    r->add_option("--grid", args->grid,
                  "Grid: auto (when the scene has enough primitives for it to pay), on, off, uniform (on, no "
                  "cell split), or a resolution NXxNYxNZ in root cells (e.g. 46x46x3), uniform; overrides the "
                  "scene")
        ->check(CLI::Validator(
            [](const std::string& text) {
                return parse_grid_option(text)
                           ? std::string()
                           : fmt::format("expected auto, on, off, uniform or NXxNYxNZ (each 1 to {}), got '{}'",
                                         limits::kMaxGridAxisCells, text);
            },
            "auto|on|off|uniform|NXxNYxNZ"));
    add_threads(r, args->threads);
    r->add_option("--stats", args->stats_file, "Write render statistics as JSON to this file");
    r->add_option("--serve", args->serve,
                  "Serve a live preview at [ADDRESS:]PORT (address default 127.0.0.1, this machine only; port 0: "
                  "any free one): a web page showing the image after every pass, with a Stop button")
        ->check(accepted_by([](const std::string& text) { live::parse_endpoint(text); }, "[ADDRESS:]PORT"));
    r->add_option("--reference", args->reference,
                  "Reference image (.exr or .hdr, linear) of the same size: the summary gives the RMSE against it, "
                  "and the live preview plots it against time");
    r->add_option("--checkpoint", args->checkpoint,
                  "Write the image so far (with --samples, the partial file of the samples so far) every this many "
                  "seconds, replacing the output atomically, so a render that is killed leaves a usable file")
        ->check(positive_seconds());
    r->add_flag("--variance", args->variance,
                "Write the variance of each pixel's mean radiance beside the image, as the layer variance.R, "
                "variance.G, variance.B of the output (.exr), for telling noise from error (vkrt compare --test)");
    r->add_option("--passes", args->passes,
                  "Write render passes beside the image as layers of the output (.exr), each averaged over the "
                  "pixel's samples: albedo (albedo.R/G/B: the first hit's base colour), normal (N.X/Y/Z: its shading "
                  "normal, world space), depth (Z: its distance from the eye, over the samples that hit; infinite "
                  "where none did); comma-separated, e.g. albedo,normal,depth")
        ->check(accepted_by([](const std::string& text) { parse_passes(text); }, "albedo,normal,depth"));
    add_validate(r, args->validate);
    add_quiet(r, args->quiet);
    // A partial file is a fixed range of samples: a count or a time budget would
    // contradict it.
    samples->excludes("--spp")->excludes("--time");
    return {r, [args] { return run_render(*args); }};
}

}  // namespace vkrt::cli
