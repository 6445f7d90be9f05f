#pragma once
// `vkrt bench`'s command-to-image table: each scene rendered by a separate
// `vkrt render` process, as a user runs it, timed from start to exit, with the
// phases and peak resident memory its --stats report (docs/bench.md#command-to-image).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace vkrt::bench {

struct ProcessScene {
    std::string label;
    std::string file;
};

struct ProcessRow {
    std::string scene;
    std::string backend;
    std::string failed;  // non-empty: why there are no figures
    // Medians over the runs.
    double whole_seconds = 0.0;
    double load_seconds = 0.0;
    double setup_seconds = 0.0;  // flatten + grid + device set-up
    double render_seconds = 0.0;
    double peak_mib = 0.0;
};

struct ProcessPlan {
    std::string executable;  // this vkrt
    std::vector<std::string> backends;
    std::string device;      // empty: the default
    std::uint32_t runs = 3;
    std::string scratch;     // directory for the images and stats files
    bool quiet = false;
};

// Runs interleave the scenes and backends, as the render table's do.
std::vector<ProcessRow> measure_processes(const ProcessPlan& plan, const std::vector<ProcessScene>& scenes);

void write_process_markdown(std::ostream& out, const std::vector<ProcessRow>& rows);

// The 100,000 spheres of scenes/gallery/h_random_spheres.json written out one
// object each (about 10 MB): what loading a large scene file costs.
std::string explicit_spheres_json(std::uint64_t count);

}  // namespace vkrt::bench
