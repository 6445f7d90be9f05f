#include "render/render.hpp"

#include <chrono>
#include <limits>
#include <memory>
#include <stdexcept>

#include "render/fingerprint.hpp"
#include "render/pixel_sums.hpp"

namespace vkrt {

namespace {

// Each pixel the mean of its four corner rays; a corner whose sample was left out
// (truncated or not finite) is left out of the mean rather than counted as black.
Image average_corners(const RenderResult& result) {
    const std::uint32_t w = result.width - 1, h = result.height - 1;
    // Each corner's mean once (w = 1 where it has samples): four pixels share it,
    // and a mean is a division of exact 96-bit sums.
    std::vector<glm::vec4> means(result.sums.size());
    for (std::size_t i = 0; i < means.size(); ++i) {
        const kernel::PixelSum& corner = result.sums[i];
        means[i] = samples_summed(corner) > 0 ? glm::vec4(mean_radiance(corner), 1.0f) : glm::vec4(0.0f);
    }
    Image image(w, h);
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) {
            glm::vec3 sum(0.0f);
            float valid = 0.0f;
            for (std::uint32_t dy = 0; dy < 2; ++dy) {
                for (std::uint32_t dx = 0; dx < 2; ++dx) {
                    const glm::vec4& m = means[std::size_t(y + dy) * result.width + x + dx];
                    sum += glm::vec3(m);
                    valid += m.w;
                }
            }
            const glm::vec3 c = valid > 0.0f ? sum / valid : glm::vec3(0.0f);
            const std::size_t p = std::size_t(y) * w + x;
            image.rgb[p * 3 + 0] = c.r;
            image.rgb[p * 3 + 1] = c.g;
            image.rgb[p * 3 + 2] = c.b;
        }
    }
    return image;
}

std::vector<std::uint32_t> pixel_decisions(const RenderResult& result, bool corners) {
    auto at = [&](std::uint32_t x, std::uint32_t y) {
        return result.counters[std::size_t(y) * result.width + x].tree[kernel::TREE_DECISIONS];
    };
    const std::uint32_t w = corners ? result.width - 1 : result.width;
    const std::uint32_t h = corners ? result.height - 1 : result.height;
    std::vector<std::uint32_t> out(std::size_t(w) * h);
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) {
            out[std::size_t(y) * w + x] =
                corners ? at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1) : at(x, y);
        }
    }
    return out;
}

}  // namespace

Image resolve_image(const RenderResult& result, bool corners) {
    if (corners) return average_corners(result);
    Image image(result.width, result.height);
    for (std::size_t p = 0; p < result.sums.size(); ++p) {
        const glm::vec3 mean = mean_radiance(result.sums[p]);
        image.rgb[p * 3 + 0] = mean.r;
        image.rgb[p * 3 + 1] = mean.g;
        image.rgb[p * 3 + 2] = mean.b;
    }
    return image;
}

ImageLayer variance_layer(const RenderResult& result) {
    ImageLayer layer{"variance", {"R", "G", "B"}, std::vector<float>(result.sums.size() * 3)};
    for (std::size_t p = 0; p < result.sums.size(); ++p) {
        const glm::dvec3 v = variance_of_mean(result.sums[p]);
        for (int c = 0; c < 3; ++c) layer.values[p * 3 + std::size_t(c)] = static_cast<float>(v[c]);
    }
    return layer;
}

std::vector<ImageLayer> pass_layers(const RenderResult& result, const std::vector<RenderPass>& passes) {
    if (result.passes.size() != result.sums.size()) {
        throw std::logic_error("pass_layers: the render kept no passes (HAS_PASSES)");
    }
    const std::size_t pixels = result.sums.size();
    ImageLayer albedo{"albedo", {"R", "G", "B"}, std::vector<float>(pixels * 3)};
    ImageLayer normal{"N", {"X", "Y", "Z"}, std::vector<float>(pixels * 3)};
    ImageLayer depth{"", {"Z"}, std::vector<float>(pixels)};
    for (std::size_t p = 0; p < pixels; ++p) {
        const kernel::Counters& c = result.counters[p];
        const PassMeans m = pass_means(result.passes[p], c.rays[kernel::RAYS_EYE], c.tree[kernel::TREE_EYE_HITS]);
        for (std::size_t k = 0; k < 3; ++k) {
            albedo.values[p * 3 + k] = static_cast<float>(m.albedo[glm::length_t(k)]);
            normal.values[p * 3 + k] = static_cast<float>(m.normal[glm::length_t(k)]);
        }
        depth.values[p] = static_cast<float>(m.depth);
    }
    std::vector<ImageLayer> layers;
    for (const RenderPass pass : passes) {
        layers.push_back(pass == RenderPass::Albedo   ? albedo
                         : pass == RenderPass::Normal ? normal
                                                      : depth);
    }
    return layers;
}

std::uint64_t total_rays(const RenderResult& result) {
    std::uint64_t rays = 0;
    for (const kernel::Counters& c : result.counters) {
        for (std::uint32_t kind : {kernel::RAYS_EYE, kernel::RAYS_SHADOW, kernel::RAYS_REFLECTION,
                                   kernel::RAYS_REFRACTION}) {
            rays += c.rays[kind];
        }
        rays += c.paths[kernel::PATHS_BOUNCE_RAYS];
    }
    return rays;
}

RenderStats collect_stats(const FlatScene& scene, const Backend& backend, const RenderResult& result) {
    RenderStats s;
    s.backend = backend.name();
    s.device = backend.device_name();
    s.width = result.width;
    s.height = result.height;
    s.samples_per_pixel = scene.samples_per_pixel;
    for (const kernel::Counters& c : result.counters) {
        s.eye_rays += c.rays[kernel::RAYS_EYE];
        s.shadow_rays += c.rays[kernel::RAYS_SHADOW];
        s.reflection_rays += c.rays[kernel::RAYS_REFLECTION];
        s.refraction_rays += c.rays[kernel::RAYS_REFRACTION];
        s.eye_hits += c.tree[kernel::TREE_EYE_HITS];
        s.bounce_rays += c.paths[kernel::PATHS_BOUNCE_RAYS];
        s.roulette_ended += c.paths[kernel::PATHS_ROULETTE];
        s.paper_dropped += c.paths[kernel::PATHS_PAPER_DROPPED];
        s.dropped_low_weight += c.tree[kernel::TREE_DROPPED_WEIGHT];
        s.dropped_stack_full += c.tree[kernel::TREE_DROPPED_STACK];
        s.cells_visited += c.work[kernel::WORK_CELLS];
        s.intersection_tests += c.work[kernel::WORK_TESTS];
        s.truncated_samples += c.work[kernel::WORK_TRUNCATED];
        s.nonfinite_samples += c.work[kernel::WORK_NONFINITE];
    }
    for (const kernel::PixelSum& sum : result.sums) s.clamped_samples += samples_clamped(sum);
    s.setup_seconds = result.setup_seconds;
    s.render_seconds = result.render_seconds;
    s.longest_submit_seconds = result.longest_submit_seconds;
    s.data_paths = result.data_paths;
    s.slabs = result.slabs;
    s.tile_width = result.tile_width;
    s.tile_height = result.tile_height;
    s.device_resets = result.device_resets;
    s.triangles = scene.triangles.size();
    s.emitters = scene.emitters.size();
    s.textures = scene.textures.size();
    s.texture_bytes = scene.texture_words.size() * sizeof(std::uint32_t);
    s.instanced_meshes = scene.instances.meshes;
    s.instances = scene.instances.placements;
    s.features = scene.features;
    s.buffers = scene.built_buffers();
    s.validation_messages = backend.validation_messages();
    s.loop_budget = kernel::loop_budget(scene.params);
    s.grid = scene.grid;
    return s;
}

RenderOutcome render_scene(const Scene& scene, Backend& backend, const RenderPlan& plan,
                           const ProgressiveCallback& progress) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    const auto step = [&](const std::string& what) {
        if (plan.on_step) plan.on_step(what);
    };
    step("flattening the scene (grid, area lights, textures)");
    const FlatScene gpu = flatten_scene(scene, backend.accel_policy());
    const auto flattened = clock::now();
    step(std::string("setting up the ") + backend.name() + " backend (pipeline, uploads)");
    const std::unique_ptr<RenderSession> session = backend.begin(gpu);
    step("rendering the first pass");
    const SampleRange samples{plan.first_sample, plan.samples.value_or(gpu.samples_per_pixel)};
    const std::uint64_t fingerprint = scene_fingerprint(gpu);
    ProgressiveRender render(*session, {samples, plan.seconds});
    bool stopped_by_request = false;
    while (!stopped_by_request && render.next_pass(std::numeric_limits<std::uint32_t>::max(), progress)) {
        if (plan.after_pass) {
            stopped_by_request = !plan.after_pass(PassView{render.total(), gpu.corners, plan.first_sample,
                                                           render.samples_done(), samples.count, render.passes(),
                                                           render.elapsed(), render.seconds_left(), fingerprint});
        }
    }
    RenderResult result = render.take_total();
    result.setup_seconds = session->setup_seconds();
    RenderOutcome out{resolve_image(result, gpu.corners), collect_stats(gpu, backend, result),
                      pixel_decisions(result, gpu.corners), {}, gpu.corners};
    out.stats.width = out.image.width;
    out.stats.height = out.image.height;
    out.stats.samples_per_pixel = render.samples_done();
    out.stats.first_sample = plan.first_sample;
    out.stats.passes = render.passes();
    out.stats.stopped_by_time = render.stopped_by_time();
    out.stats.stopped_by_request = stopped_by_request && render.samples_done() < samples.count;
    out.stats.pass_seconds = render.seconds();
    out.sums = std::move(result);
    out.fingerprint = fingerprint;
    out.stats.flatten_seconds = std::chrono::duration<double>(flattened - start).count();
    out.stats.total_seconds = std::chrono::duration<double>(clock::now() - start).count();
    return out;
}

}  // namespace vkrt
