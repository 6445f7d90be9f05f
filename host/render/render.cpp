#include "render/render.hpp"

#include <chrono>

namespace vkrt {

Image resolve_image(const RenderResult& result) {
    Image image(result.width, result.height);
    for (std::size_t p = 0; p < result.accum.size(); ++p) {
        const glm::vec4& sum = result.accum[p];
        const float scale = sum.a > 0.0f ? 1.0f / sum.a : 0.0f;
        image.rgb[p * 3 + 0] = sum.r * scale;
        image.rgb[p * 3 + 1] = sum.g * scale;
        image.rgb[p * 3 + 2] = sum.b * scale;
    }
    return image;
}

RenderStats collect_stats(const SceneGpu& scene, const Backend& backend, const RenderResult& result) {
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
        s.cells_visited += c.work[kernel::WORK_CELLS];
        s.intersection_tests += c.work[kernel::WORK_TESTS];
        s.truncated_samples += c.work[kernel::WORK_TRUNCATED];
        s.nonfinite_samples += c.work[kernel::WORK_NONFINITE];
    }
    s.setup_seconds = result.setup_seconds;
    s.render_seconds = result.render_seconds;
    s.features = scene.features;
    s.buffers = scene.built_buffers();
    s.validation_messages = backend.validation_messages();
    s.loop_budget = scene.params.limits.x;
    s.grid = scene.grid;
    return s;
}

RenderOutcome render_scene(const Scene& scene, Backend& backend, const ProgressCallback& progress) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    const SceneGpu gpu = build_scene_gpu(scene, backend.accel_policy());
    const auto flattened = clock::now();
    const RenderResult result = backend.render(gpu, SampleRange{0, gpu.samples_per_pixel}, progress);
    RenderOutcome out{resolve_image(result), collect_stats(gpu, backend, result)};
    out.stats.flatten_seconds = std::chrono::duration<double>(flattened - start).count();
    out.stats.total_seconds = std::chrono::duration<double>(clock::now() - start).count();
    return out;
}

}  // namespace vkrt
