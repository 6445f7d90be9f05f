#pragma once
// The rows `vkrt bench --spd` measures and the forms it writes them in: a Markdown
// table (published counts beside vkrt's, the difference in percent, the times) and
// CSV. docs/bench.md says what each column means.
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bench/spd_published.hpp"

namespace vkrt::bench {

// One (SPD scene, backend) measurement: ray counts from the first run (every run
// must give the same), times as medians over the runs.
struct SpdRow {
    std::string scene;             // the file's stem
    std::uint64_t primitives = 0;  // spheres + triangles + rings + cylinders, after tessellation
    std::string backend;           // "vulkan" or "cpu"
    std::uint32_t width = 0;       // the image; eye rays go through its (width+1) x (height+1) corners
    std::uint32_t height = 0;

    std::uint64_t eye_rays = 0;
    SpdCounts counts;
    std::optional<SpdCounts> published;  // none: the scene has no published row
    std::uint64_t dropped_rays = 0;      // secondary rays not traced (weight or stack); the SPD rules drop none
    std::uint64_t truncated_samples = 0; // stopped by the loop budget
    bool counts_identical = true;        // every run traced the same rays

    double load_seconds = 0.0;        // reading the file, tessellating cones
    double flatten_seconds = 0.0;     // Scene -> GPU arrays, the grid build included
    double grid_build_seconds = 0.0;  // the grid build alone (part of flatten)
    double setup_seconds = 0.0;       // backend set-up: pipeline, buffers, uploads
    double preprocess_seconds = 0.0;  // median over runs of load + flatten + setup
    double render_seconds = 0.0;      // the sample loop (GPU timestamps on Vulkan)

    std::uint64_t rays() const;  // every ray: eye, reflection, refraction, shadow
    double mrays_per_second() const;
    // The kinds whose count is more than 10% off the published one, by name; empty
    // when all are within (or the scene has no published row).
    std::vector<std::string> kinds_outside_10_percent() const;
};

// (got - published) / published in percent: 0 when both are 0, none (an infinite
// difference) when only the published count is 0.
std::optional<double> difference_percent(std::uint64_t got, std::uint64_t published);

void write_spd_markdown(std::ostream& out, const std::vector<SpdRow>& rows);
void write_spd_csv(std::ostream& out, const std::vector<SpdRow>& rows);

}  // namespace vkrt::bench
