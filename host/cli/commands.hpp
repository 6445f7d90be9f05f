#pragma once
// The subcommands of the vkrt program. Each returns the process exit status and
// throws for errors the caller reports as "error: <message>" (exit status 1).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cli/options.hpp"
#include "render/render.hpp"
#include "scene/scene.hpp"

namespace vkrt::cli {

struct RenderArgs {
    std::string scene;
    std::string output;  // empty: <scene name>.png in the current directory
    std::string backend = "vulkan";
    std::string device;
    std::optional<std::uint32_t> width;
    std::optional<std::uint32_t> height;
    std::optional<std::uint32_t> spp;
    std::optional<double> time;  // seconds of progressive passes; with spp, whichever ends first
    std::string samples;         // "A:B": render samples [A, B) only, to a partial file
    std::optional<std::uint32_t> seed;
    std::string sampler;  // empty: the scene's; else sobol or hash
    std::optional<std::uint32_t> bounces;  // global mode's max_bounces
    std::string background;                // empty: the scene's; else a colour (parse_colour)
    std::string environment;               // empty: the scene's; else an image file around the scene
    std::optional<double> environment_intensity;  // of the scene's environment or --environment's
    std::optional<double> environment_rotation;   // degrees about its up axis
    DisplayOptions display;
    std::string grid;    // empty: the scene's choice; else auto, on or off
    unsigned threads = 0;
    std::string stats_file;
    std::string serve;           // "[ADDRESS:]PORT" of the live preview; empty: none
    std::string reference;       // linear image to report the error against; empty: none
    std::optional<double> checkpoint;  // seconds between writes of the image so far
    bool variance = false;  // the image's file carries the variance of each pixel's mean
    std::string passes;     // "albedo,normal,depth" or some of them: render passes as layers; empty: none
    bool validate = false;
    bool quiet = false;
};

// The --grid value: auto, on, off, or a resolution "NXxNYxNZ" (cells per axis,
// each 1 to limits::kMaxGridAxisCells). Empty optional when the text is none of these.
std::optional<GridSettings> parse_grid_option(const std::string& text);

// The --passes value: names from albedo, normal and depth, separated by commas, each
// once. Throws std::invalid_argument naming what was wrong.
std::vector<RenderPass> parse_passes(const std::string& text);

struct CompareArgs {
    std::string a;
    std::string b;
    std::optional<double> max_rmse;
    std::optional<double> max_abs;
    double threshold = 1e-3;
    std::vector<std::string> metrics;  // of kCompareMetrics, printed one a line
    std::string difference;            // a .png of the signed difference a - b; empty: none
    std::optional<double> difference_range;  // the difference at the colour map's ends; default the largest
    bool test = false;       // the Z-test of A (with variance) against B (image/z_test.hpp)
    double alpha = 0.01;     // its familywise level
    std::string p_values;    // an .exr of each pixel channel's p-value; empty: none
};

// The names --metric takes: mae, mse, rmse, relmse (b the reference), ssim.
inline constexpr std::array<const char*, 5> kCompareMetrics = {"mae", "mse", "rmse", "relmse", "ssim"};

struct MergeArgs {
    std::vector<std::string> partials;
    std::string output;
    std::string samples;      // "A:B": the samples the partials must cover; empty: from the first to the last
    bool allow_gaps = false;  // merge even with samples missing
    bool missing = false;     // list the ranges still to render instead of merging
    std::uint32_t tasks = 0;  // with missing: cut them into about this many ranges
    DisplayOptions display;   // for an 8-bit output
    bool quiet = false;
};

struct DevicesArgs {
    bool float_profile = false;  // probe float behaviour (docs/numerics.md) instead of listing
    std::string device;          // with float_profile: only this device (as render's --device)
    std::string json;            // with float_profile: also write the profile here
    bool limits = false;         // print each device's limits and heuristics
    std::string profile;         // with limits: clamp them to this profile first
};

int run_render(const RenderArgs& args);
int run_merge(const MergeArgs& args);
int run_compare(const CompareArgs& args);
int run_devices(const DevicesArgs& args);

}  // namespace vkrt::cli
