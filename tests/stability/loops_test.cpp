// The numerical-stability suite (docs/numerics.md): no loop runs unbounded. Grid
// traversal, the bounce loops and the reflection/refraction stack end for any input,
// zero, negative-zero, tiny, NaN and infinite direction components included. Eye rays of every combination of such
// components (and origins inside the scene, on the grid's boundary and non-finite) are
// traced through a scene that has every loop the kernel has: the grid walk, the point
// and area light loops, the mirror/glass ray tree, and global mode's bounce loop with
// either estimator. Each sample must end by itself (the loop budget, a backstop, never
// fires) and leave either a finite radiance that is added to its pixel or a non-finite
// one that is counted and kept out. Through the reference backend, which runs the same
// kernel text; the Vulkan backend's budget and counting are tested in
// kernel/loop_budget_test.cpp and stability/scenes_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "kernel/kernel.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/pixel_sums.hpp"
#include "scene/load_scene.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::vec3;
using kernel::vec4;

// Mirrors, glass, an emitter, a point light, every primitive kind and a forced grid,
// inside a closed room (two walls mirrors), so that every ordinary direction hits.
Scene every_loop_scene(const std::string& render) {
    const std::filesystem::path file = test::temp_dir("loops") / "scene.json";
    std::ofstream(file) << fmt::format(R"({{
      "camera": {{ "eye": [0, 1, 5], "look_at": [0, 0.5, 0], "width": 4, "height": 4 }},
      "render": {{ {}, "grid": {{ "resolution": [4, 4, 4] }} }},
      "materials": {{
        "mirror": {{ "diffuse": [0.2, 0.2, 0.2], "reflect": [0.8, 0.8, 0.8] }},
        "glass": {{ "transmit": [0.9, 0.9, 0.9], "ior": 1.5 }},
        "matte": {{ "diffuse": [0.7, 0.6, 0.5], "specular": [1, 1, 1], "ks": 0.3 }},
        "lamp": {{ "emission": [3, 3, 3] }}
      }},
      "lights": [ {{ "type": "point", "position": [2, 4, 3] }} ],
      "objects": [
        {{ "type": "sphere", "center": [-1, 0.5, 0], "radius": 0.5, "material": "mirror" }},
        {{ "type": "sphere", "center": [1, 0.5, 0], "radius": 0.5, "material": "glass" }},
        {{ "type": "sphere", "center": [0, 3, 0], "radius": 0.3, "material": "lamp" }},
        {{ "type": "quad", "corner": [-6, 0, -6], "edge1": [0, 0, 12], "edge2": [12, 0, 0], "material": "matte" }},
        {{ "type": "quad", "corner": [-6, 6, -6], "edge1": [12, 0, 0], "edge2": [0, 0, 12], "material": "matte" }},
        {{ "type": "quad", "corner": [-6, 0, -6], "edge1": [12, 0, 0], "edge2": [0, 6, 0], "material": "mirror" }},
        {{ "type": "quad", "corner": [-6, 0, 6], "edge1": [0, 6, 0], "edge2": [12, 0, 0], "material": "matte" }},
        {{ "type": "quad", "corner": [-6, 0, -6], "edge1": [0, 6, 0], "edge2": [0, 0, 12], "material": "mirror" }},
        {{ "type": "quad", "corner": [6, 0, -6], "edge1": [0, 0, 12], "edge2": [0, 6, 0], "material": "matte" }},
        {{ "type": "ring", "center": [0, 0.01, 1], "normal": [0, 1, 0], "inner": 0.1, "outer": 0.4, "material": "mirror" }},
        {{ "type": "cylinder", "base": [0, 0, -1], "top": [0, 1, -1], "radius": 0.2, "capped": true, "material": "glass" }}
      ]
    }})", render);
    return load_scene(file);
}

std::vector<float> tricky_components() {
    const float inf = std::numeric_limits<float>::infinity();
    return {0.0f, -0.0f, 1e-30f, -1e-30f, 1.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(), inf, -inf};
}

struct Tally {
    std::size_t samples = 0, finite = 0, nonfinite = 0, hits = 0;
};

// Every direction of tricky components from each origin, as the eye ray of pixel
// (0, 0): with cam_right = cam_down = 0 the eye ray's direction is
// unit_vector(cam_corner), whatever the pixel.
Tally trace_everything(const Scene& scene) {
    const FlatScene gpu = flatten_scene(scene);
    EXPECT_FALSE(gpu.grid_nodes.empty()) << "the grid must be on";
    kernel::Kernel k = make_kernel(gpu);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // In the kernel's coordinates, whatever the host made them.
    const vec3 lo = kernel::grid_min(gpu.params), hi = kernel::grid_max(gpu.params);
    const std::vector<vec3> origins = {
        kernel::camera_eye(gpu.params),  // the eye, outside the grid
        (lo + hi) * 0.5f,          // inside it
        lo,                        // on a corner of it
        vec3(nan, lo.y, lo.z),
        vec3(lo.x, std::numeric_limits<float>::infinity(), lo.z),
    };
    Tally t;
    const std::vector<float> c = tricky_components();
    for (const vec3& origin : origins) {
        for (float x : c) {
            for (float y : c) {
                for (float z : c) {
                    kernel::set_camera_eye(k.params, origin);
                    kernel::set_camera_corner(k.params, vec3(x, y, z));
                    kernel::set_camera_right(k.params, vec3(0.0f));
                    kernel::set_camera_down(k.params, vec3(0.0f));
                    const auto s = k.render_sample(0, 0, 0);
                    EXPECT_FALSE(s.truncated) << "a loop did not end by itself: origin (" << origin.x << ", "
                                              << origin.y << ", " << origin.z << "), direction (" << x << ", " << y
                                              << ", " << z << ")";
                    kernel::PixelSum sum{};
                    kernel::Counters counters{};
                    k.accumulate_sample(s, sum, counters);
                    const bool finite = std::isfinite(s.radiance.x + s.radiance.y + s.radiance.z);
                    // A finite sample is added; a non-finite one is counted, never added.
                    EXPECT_EQ(samples_summed(sum), finite && !s.dropped && !s.truncated ? 1u : 0u);
                    EXPECT_EQ(counters.work[kernel::WORK_NONFINITE], finite || s.dropped || s.truncated ? 0u : 1u);
                    EXPECT_TRUE(std::isfinite(radiance_sum(sum).x + radiance_sum(sum).y + radiance_sum(sum).z));
                    ++t.samples;
                    t.hits += s.eye_hits;
                    (finite ? t.finite : t.nonfinite) += 1;
                }
            }
        }
    }
    return t;
}

void report(const char* mode, const Tally& t) {
    std::printf("%s: %zu samples, %zu eye rays hit, %zu finite, %zu non-finite (counted, not added)\n", mode,
                t.samples, t.hits, t.finite, t.nonfinite);
    EXPECT_GT(t.finite, t.samples / 2) << "most directions are ordinary and must shade";
    // Of the 9^3 directions only the 152 with a component of +-1 and no NaN or infinity
    // are ordinary (the rest become NaN in unit_vector, or a zero vector); from the
    // eye and the room's centre all of those hit, from the grid's corner about half.
    EXPECT_GE(t.hits, 2u * 152u) << "the rays must reach the scene for the loops to run";
}

// max_depth 8 with no weight cut-off: a glass hit spawns two rays, so the tree may hold
// up to 2^9 rays, each walking the grid and the lights.
TEST(UnboundedInput, LocalRayTreeAndGridEndForAnyDirection) {
    report("local", trace_everything(every_loop_scene(R"("max_depth": 8, "min_weight": 0)")));
}

// The tree's size is exponential in max_depth: at 64 with no weight cut-off, glass
// between mirrors asks for more rays than any invocation may trace (docs/architecture.md,
// "Bounded work per invocation"). There the loop budget is the mechanism, and the
// sample must be stopped, counted as truncated and kept out of the pixel.
TEST(UnboundedInput, AnExponentialRayTreeIsStoppedAndCounted) {
    const FlatScene gpu = flatten_scene(every_loop_scene(R"("max_depth": 64, "min_weight": 0)"));
    kernel::Kernel k = make_kernel(gpu);
    kernel::set_camera_right(k.params, vec3(0.0f));
    kernel::set_camera_down(k.params, vec3(0.0f));
    kernel::set_camera_corner(k.params, vec3(0.0f, 0.0f, -1.0f));  // through the glass cylinder, between mirrors
    const auto s = k.render_sample(0, 0, 0);
    EXPECT_TRUE(s.truncated);
    kernel::PixelSum sum{};
    kernel::Counters counters{};
    k.accumulate_sample(s, sum, counters);
    EXPECT_EQ(counters.work[kernel::WORK_TRUNCATED], 1u);
    EXPECT_EQ(samples_summed(sum), 0u);
}

TEST(UnboundedInput, PathTracingEndsForAnyDirection) {
    report("path", trace_everything(every_loop_scene(R"("mode": "global", "max_bounces": 1000, "spp": 1)")));
}

TEST(UnboundedInput, PaperEstimatorEndsForAnyDirection) {
    report("paper", trace_everything(every_loop_scene(R"("mode": "global", "estimator": "paper", "max_bounces": 3, "spp": 1)")));
}

}  // namespace
}  // namespace vkrt
