// The --stats report (host/render/stats_json.cpp): the fields docs/cli.md
// documents, each from its member of RenderStats, and the figures derived from
// them (total rays, work per ray, rays per second), including their zero cases.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "flatten/features.hpp"
#include "render/render.hpp"
#include "render/stats_json.hpp"

namespace {

using namespace vkrt;
using nlohmann::json;

// Every member a different value, so that a field read from the wrong member shows.
RenderStats distinct_stats() {
    RenderStats s;
    s.backend = "vulkan";
    s.device = "llvmpipe";
    s.width = 64;
    s.height = 48;
    s.samples_per_pixel = 9;
    s.first_sample = 3;
    s.passes = 5;
    s.stopped_by_time = true;
    s.stopped_by_request = false;
    s.eye_rays = 1000;
    s.shadow_rays = 200;
    s.reflection_rays = 30;
    s.refraction_rays = 4;
    s.bounce_rays = 6;
    s.eye_hits = 700;
    s.roulette_ended = 11;
    s.paper_dropped = 12;
    s.dropped_low_weight = 13;
    s.dropped_stack_full = 14;
    s.cells_visited = 310;
    s.intersection_tests = 4960;
    s.truncated_samples = 15;
    s.nonfinite_samples = 16;
    s.clamped_samples = 17;
    s.load_seconds = 0.5;
    s.decode_seconds = 0.25;
    s.first_pass_seconds = 1.5;
    s.flatten_seconds = 0.125;
    s.setup_seconds = 0.75;
    s.render_seconds = 2.0;
    s.pass_seconds = 2.5;
    s.longest_submit_seconds = 0.0625;
    s.total_seconds = 4.0;
    s.peak_resident_bytes = 123456789;
    s.data_paths = "scene: texel buffers, params: uniform buffer";
    s.slabs = 2;
    s.tile_width = 256;
    s.tile_height = 64;
    s.device_resets = 1;
    s.triangles = 18;
    s.emitters = 19;
    s.textures = 20;
    s.texture_bytes = 21;
    s.instanced_meshes = 3;
    s.instances = 17;
    s.features.set(Feature::HAS_SPHERES, true);
    s.features.set(Feature::HAS_SHADOWS, true);
    s.buffers = {{"spheres", 96}, {"materials", 720}};
    s.validation_messages = 22;
    s.loop_budget = 60000;
    s.grid.used = true;
    s.grid.reason = "auto";
    s.grid.outside = {"triangles: 2"};
    s.grid.resolution = {4, 5, 6};
    s.grid.cells = 120;
    s.grid.levels = 1;
    s.grid.references = 300;
    s.grid.bytes = 1680;
    s.grid.build_seconds = 0.01;
    return s;
}

std::set<std::string> keys_of(const json& object) {
    std::set<std::string> keys;
    for (const auto& [key, value] : object.items()) keys.insert(key);
    return keys;
}

TEST(StatsJson, HoldsTheDocumentedFieldsAndNoOthers) {
    const json j = stats_to_json(distinct_stats());
    EXPECT_EQ(keys_of(j), (std::set<std::string>{
                              "backend", "buffers", "device", "device_plan", "features", "first_sample", "grid",
                              "height", "memory", "passes", "paths", "ray_tree", "rays", "rays_per_second", "samples",
                              "samples_per_pixel", "scene", "seconds", "stopped_by_request", "stopped_by_time",
                              "validation_messages", "width", "work"}));
    EXPECT_EQ(keys_of(j["rays"]),
              (std::set<std::string>{"total", "eye", "shadow", "reflection", "refraction", "bounce", "eye_hits"}));
    EXPECT_EQ(keys_of(j["seconds"]), (std::set<std::string>{"load", "decode", "flatten", "setup", "first_pass", "render",
                                                            "passes", "longest_submission", "total"}));
    EXPECT_EQ(keys_of(j["grid"]), (std::set<std::string>{"used", "reason", "outside", "resolution", "levels", "cells",
                                                         "references", "bytes", "build_seconds"}));
}

TEST(StatsJson, EachFieldFromItsMember) {
    const json j = stats_to_json(distinct_stats());
    EXPECT_EQ(j["backend"], "vulkan");
    EXPECT_EQ(j["device"], "llvmpipe");
    EXPECT_EQ(j["width"], 64);
    EXPECT_EQ(j["height"], 48);
    EXPECT_EQ(j["samples_per_pixel"], 9);
    EXPECT_EQ(j["first_sample"], 3);
    EXPECT_EQ(j["passes"], 5);
    EXPECT_EQ(j["stopped_by_time"], true);
    EXPECT_EQ(j["stopped_by_request"], false);
    EXPECT_EQ(j["rays"], json::parse(R"({"total": 1240, "eye": 1000, "shadow": 200, "reflection": 30,
                                         "refraction": 4, "bounce": 6, "eye_hits": 700})"));
    EXPECT_EQ(j["paths"], json::parse(R"({"roulette_ended": 11, "paper_dropped": 12})"));
    EXPECT_EQ(j["ray_tree"], json::parse(R"({"dropped_low_weight": 13, "dropped_stack_full": 14})"));
    EXPECT_EQ(j["samples"], json::parse(R"({"truncated": 15, "nonfinite": 16, "clamped": 17, "loop_budget": 60000})"));
    EXPECT_EQ(j["seconds"], json::parse(R"({"load": 0.5, "decode": 0.25, "flatten": 0.125, "setup": 0.75,
                                            "first_pass": 1.5, "render": 2.0, "passes": 2.5,
                                            "longest_submission": 0.0625, "total": 4.0})"));
    EXPECT_EQ(j["scene"], json::parse(R"({"triangles": 18, "emitters": 19, "textures": 20, "texture_bytes": 21,
                                          "instanced_meshes": 3, "instances": 17})"));
    EXPECT_EQ(j["memory"], json::parse(R"({"peak_resident_bytes": 123456789})"));
    EXPECT_EQ(j["buffers"], json::parse(R"({"spheres": 96, "materials": 720})"));
    EXPECT_EQ(j["validation_messages"], 22);
    EXPECT_EQ(j["device_plan"], json::parse(R"({"data_paths": "scene: texel buffers, params: uniform buffer",
                                                "slabs": 2, "tile": [256, 64], "device_resets": 1})"));
    EXPECT_EQ(j["grid"], json::parse(R"({"used": true, "reason": "auto", "outside": ["triangles: 2"],
                                         "resolution": [4, 5, 6], "levels": 1, "cells": 120, "references": 300,
                                         "bytes": 1680, "build_seconds": 0.01})"));
    // Features by name, in the order of kernel/features.glsl.
    const std::vector<std::string> kept = j["features"]["kept"];
    EXPECT_EQ(kept, (std::vector<std::string>{"spheres", "shadows"}));
    const std::vector<std::string> left_out = j["features"]["left_out"];
    EXPECT_EQ(left_out.size(), kFeatureCount - 2);
    EXPECT_EQ(left_out.front(), "triangles");
}

TEST(StatsJson, FiguresPerRayAndPerSecond) {
    const json j = stats_to_json(distinct_stats());
    // 1240 rays in 2 seconds; 310 cells and 4960 tests over them.
    EXPECT_EQ(j["rays_per_second"], 620.0);
    EXPECT_EQ(j["work"], json::parse(R"({"cells_visited": 310, "intersection_tests": 4960, "cells_per_ray": 0.25,
                                         "tests_per_ray": 4.0})"));
}

TEST(StatsJson, NoRaysOrNoTimeGiveZeroNotNaN) {
    RenderStats s = distinct_stats();
    s.render_seconds = 0.0;
    EXPECT_EQ(stats_to_json(s)["rays_per_second"], 0.0);
    s.eye_rays = s.shadow_rays = s.reflection_rays = s.refraction_rays = s.bounce_rays = 0;
    const json work = stats_to_json(s)["work"];
    EXPECT_EQ(work["cells_per_ray"], 0.0);
    EXPECT_EQ(work["tests_per_ray"], 0.0);
    // An empty report is still well formed: every number a number.
    const json empty = stats_to_json(RenderStats{});
    EXPECT_EQ(json::parse(empty.dump()), empty);
    EXPECT_EQ(empty["buffers"], json::object());
}

}  // namespace
