// vkrt: command-line parsing only; the work is in cli/commands.cpp.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/commands.hpp"
#include "scene/limits.hpp"

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
        ->check(CLI::Range(1u, limits::kMaxImageSide));
    r->add_option("--height", render.height, "Image height, overrides the scene")
        ->check(CLI::Range(1u, limits::kMaxImageSide));
    r->add_option("--spp", render.spp, "Samples per pixel (default: the scene's, else aa*aa)")
        ->check(CLI::Range(1u, limits::kMaxSpp));
    r->add_option("--seed", render.seed, "Random seed, overrides the scene");
    r->add_option("--threads", render.threads, "CPU threads for the cpu backend (default: all)")
        ->check(CLI::Range(0u, 1024u));
    r->add_option("--stats", render.stats_file, "Write render statistics as JSON to this file");
    r->add_flag("--validate", render.validate,
                "Enable the Vulkan validation layer; any message makes the render fail");
    r->add_flag("-q,--quiet", render.quiet, "Print nothing but errors");

    cli::CompareArgs compare;
    CLI::App* c = app.add_subcommand("compare", "Compare two images; exit 1 when over a given bound");
    c->add_option("a", compare.a, "First image")->required();
    c->add_option("b", compare.b, "Second image")->required();
    c->add_option("--max-rmse", compare.max_rmse, "Fail when the RMSE is above this");
    c->add_option("--max-abs", compare.max_abs, "Fail when the largest channel difference is above this");
    c->add_option("--threshold", compare.threshold, "Per-channel difference counted as a differing pixel")
        ->capture_default_str();

    app.add_subcommand("devices", "List the Vulkan devices");

    CLI11_PARSE(app, argc, argv);
    try {
        if (r->parsed()) return cli::run_render(render);
        if (c->parsed()) return cli::run_compare(compare);
        return cli::run_devices();
    } catch (const std::exception& e) {
        fmt::print(stderr, "error: {}\n", e.what());
        return 1;
    }
}
