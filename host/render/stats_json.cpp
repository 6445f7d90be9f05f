#include "render/stats_json.hpp"

namespace vkrt {

nlohmann::json stats_to_json(const RenderStats& s) {
    nlohmann::json buffers = nlohmann::json::object();
    for (const BufferSize& b : s.buffers) buffers[b.name] = b.bytes;
    return {
        {"backend", s.backend},
        {"device", s.device},
        {"width", s.width},
        {"height", s.height},
        {"samples_per_pixel", s.samples_per_pixel},
        {"first_sample", s.first_sample},
        {"passes", s.passes},
        {"stopped_by_time", s.stopped_by_time},
        {"stopped_by_request", s.stopped_by_request},
        {"rays", {{"total", s.rays()}, {"eye", s.eye_rays}, {"shadow", s.shadow_rays},
                  {"reflection", s.reflection_rays}, {"refraction", s.refraction_rays},
                  {"bounce", s.bounce_rays}, {"eye_hits", s.eye_hits}}},
        {"paths", {{"roulette_ended", s.roulette_ended}, {"paper_dropped", s.paper_dropped}}},
        {"ray_tree", {{"dropped_low_weight", s.dropped_low_weight}, {"dropped_stack_full", s.dropped_stack_full}}},
        {"work", {{"cells_visited", s.cells_visited}, {"intersection_tests", s.intersection_tests},
                  {"cells_per_ray", s.per_ray(s.cells_visited)},
                  {"tests_per_ray", s.per_ray(s.intersection_tests)}}},
        {"grid", {{"used", s.grid.used}, {"reason", s.grid.reason}, {"outside", s.grid.outside},
                  {"resolution", s.grid.resolution}, {"levels", s.grid.levels},
                  {"cells", s.grid.cells}, {"references", s.grid.references}, {"bytes", s.grid.bytes},
                  {"build_seconds", s.grid.build_seconds}}},
        {"samples", {{"truncated", s.truncated_samples}, {"nonfinite", s.nonfinite_samples},
                     {"clamped", s.clamped_samples},
                     {"loop_budget", s.loop_budget}}},
        {"seconds", {{"load", s.load_seconds}, {"decode", s.decode_seconds}, {"flatten", s.flatten_seconds},
                     {"setup", s.setup_seconds}, {"first_pass", s.first_pass_seconds},
                     {"render", s.render_seconds}, {"passes", s.pass_seconds},
                     {"longest_submission", s.longest_submit_seconds}, {"total", s.total_seconds}}},
        {"scene", {{"triangles", s.triangles}, {"emitters", s.emitters}, {"textures", s.textures},
                   {"texture_bytes", s.texture_bytes}, {"instanced_meshes", s.instanced_meshes},
                   {"instances", s.instances}}},
        {"memory", {{"peak_resident_bytes", s.peak_resident_bytes}}},
        {"rays_per_second", s.render_seconds > 0.0 ? double(s.rays()) / s.render_seconds : 0.0},
        {"features", {{"kept", s.features.kept()}, {"left_out", s.features.left_out()}}},
        {"buffers", buffers},
        {"validation_messages", s.validation_messages},
        {"device_plan", {{"data_paths", s.data_paths}, {"slabs", s.slabs},
                         {"tile", {s.tile_width, s.tile_height}}, {"device_resets", s.device_resets}}},
    };
}

}  // namespace vkrt
