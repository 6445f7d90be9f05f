#pragma once
// The one path from a scene to an image, used by the program and the tests alike:
// Scene -> FlatScene -> backend -> per-pixel sums -> averaged linear image + stats.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "accel/grid.hpp"
#include "image/image.hpp"
#include "render/backend.hpp"
#include "render/progressive.hpp"
#include "scene/scene.hpp"
#include "flatten/flat_scene.hpp"

namespace vkrt {

struct RenderStats {
    std::string backend;
    std::string device;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t samples_per_pixel = 0;  // rendered (with a time budget, as many as fitted)
    std::uint32_t first_sample = 0;       // the first sample index rendered (split rendering)
    std::uint32_t passes = 0;             // progressive passes (render/progressive.hpp)
    bool stopped_by_time = false;         // the time budget ended the render, not the sample count
    bool stopped_by_request = false;      // a watcher (RenderPlan::after_pass) ended it, e.g. a Stop button
    std::uint64_t eye_rays = 0;
    std::uint64_t shadow_rays = 0;
    std::uint64_t reflection_rays = 0;
    std::uint64_t refraction_rays = 0;
    std::uint64_t bounce_rays = 0;          // global mode: rays after a scattering event
    std::uint64_t eye_hits = 0;             // eye rays that hit something
    std::uint64_t roulette_ended = 0;       // global mode: paths ended by Russian roulette
    std::uint64_t paper_dropped = 0;        // paper estimator: samples whose gl() was 0, not averaged
    std::uint64_t dropped_low_weight = 0;   // secondary rays not traced: weight below min_weight
    std::uint64_t dropped_stack_full = 0;   // secondary rays not traced: the ray stack was full
    std::uint64_t cells_visited = 0;       // grid cells stepped through, all rays
    std::uint64_t intersection_tests = 0;  // ray-primitive tests, all rays
    std::uint64_t truncated_samples = 0;  // stopped by the loop budget: the image is wrong there
    std::uint64_t nonfinite_samples = 0;  // discarded for NaN or infinity
    std::uint64_t clamped_samples = 0;    // a channel above SUM_SAMPLE_MAX (kernel/sums.glsl), clamped
    double load_seconds = 0.0;            // reading and parsing the scene file (set by the command)
    double decode_seconds = 0.0;          // of which decoding texture images (Scene::texture_decode_seconds)
    double first_pass_seconds = 0.0;      // from the command's start to its first pass's sums (set by the command)
    double flatten_seconds = 0.0;         // Scene -> FlatScene
    double setup_seconds = 0.0;           // backend set-up (pipelines, uploads)
    double render_seconds = 0.0;
    double pass_seconds = 0.0;            // wall clock of the passes, read-back and accumulation included
    double longest_submit_seconds = 0.0;  // Vulkan: the longest single queue submission
    double total_seconds = 0.0;
    std::uint64_t peak_resident_bytes = 0;  // the process's, once the image is written (set by the command)
    // Vulkan: the layout of the work on the device (RenderResult says more).
    std::string data_paths;
    std::uint32_t slabs = 0, tile_width = 0, tile_height = 0, device_resets = 0;
    // What the kernel was given: triangles (and quads), the area lights among all
    // primitives, texture records and the bytes of their texels.
    std::size_t triangles = 0, emitters = 0, textures = 0, texture_bytes = 0;
    // Meshes placed more than once, and their placements (copies) in all.
    std::size_t instanced_meshes = 0, instances = 0;
    FeatureSet features;
    std::vector<BufferSize> buffers;
    std::uint32_t validation_messages = 0;
    std::uint32_t loop_budget = 0;        // loop iterations allowed per invocation

    GridStats grid;

    std::uint64_t rays() const { return eye_rays + shadow_rays + reflection_rays + refraction_rays + bounce_rays; }
    double per_ray(std::uint64_t n) const { return rays() != 0 ? double(n) / double(rays()) : 0.0; }
};

struct RenderOutcome {
    Image image;
    RenderStats stats;
    // Per output pixel, the sum of its rays' decision hashes (budget.glsl): equal on
    // two backends when every ray hit the same things, was lit and shadowed alike
    // and reflected or refracted alike; what the cross-check tells flips apart by.
    std::vector<std::uint32_t> decisions;
    // The exact per-pixel sums and counters the image was resolved from (for
    // partial files), over the kernel's grid of rays (with `corners`, one larger).
    RenderResult sums;
    bool corners = false;
    std::uint64_t fingerprint = 0;  // of the flattened scene (render/fingerprint.hpp)
};

// A render as it stands after one of its passes, for whoever watches it (a live
// preview, checkpoints): the exact sums so far and how far the plan has come.
struct PassView {
    const RenderResult& total;    // every pass so far; resolve_image(total, corners) is the image
    bool corners = false;
    std::uint32_t first_sample = 0;
    std::uint32_t samples = 0;    // per pixel, done
    std::uint32_t target = 0;     // per pixel, the plan's most
    std::uint32_t passes = 0;
    double elapsed = 0.0;         // seconds since the first pass started
    double seconds_left = 0.0;    // estimated, to the sample count or the time budget
    std::uint64_t fingerprint = 0;  // of the flattened scene, as RenderOutcome's
};
// Called after every pass; false ends the render there, as a time budget running out would.
using PassObserver = std::function<bool(const PassView&)>;

// What to render of a scene: by default every sample it asks for, in one go of
// progressive passes.
struct RenderPlan {
    std::uint32_t first_sample = 0;        // the first sample index (split rendering)
    std::optional<std::uint32_t> samples;  // how many samples at most; default the scene's spp
    std::optional<double> seconds;         // a time budget (render/pass_plan.hpp)
    PassObserver after_pass;               // optional
    // Told each step before the first pass (flattening, the backend's set-up), for
    // progress on scenes that take long to prepare; optional.
    std::function<void(const std::string&)> on_step;
};

// Every ray the counters hold, of all kinds (RenderStats::rays() from the sums alone).
std::uint64_t total_rays(const RenderResult& result);

// Each pixel's sum divided by its count of good samples (black where there is none).
// The average radiance of each pixel; with `corners`, of each pixel's four corner
// rays (the result is one row and one column larger than the image).
Image resolve_image(const RenderResult& result, bool corners = false);

// The variance of each pixel's mean radiance (pixel_sums.hpp, variance_of_mean), as
// the layer "variance" (channels R, G, B) of an OpenEXR file; infinite where a pixel
// has fewer than two good samples. Not for corner rays.
ImageLayer variance_layer(const RenderResult& result);

// The render passes `vkrt render --passes` writes beside the image.
enum class RenderPass { Albedo, Normal, Depth };

// The passes' layers of an OpenEXR file from a render with HAS_PASSES (pixel_sums.hpp,
// pass_means), in the channel names compositors and denoisers read: "albedo" (R, G,
// B), "N" (X, Y, Z) and the bare channel "Z". Not for corner rays.
std::vector<ImageLayer> pass_layers(const RenderResult& result, const std::vector<RenderPass>& passes);

RenderStats collect_stats(const FlatScene& scene, const Backend& backend, const RenderResult& result);

// Renders the plan's samples in progressive passes through one backend session.
RenderOutcome render_scene(const Scene& scene, Backend& backend, const RenderPlan& plan = {},
                           const ProgressiveCallback& progress = {});

}  // namespace vkrt
