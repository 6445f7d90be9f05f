#pragma once
// `vkrt bench`: rays per second for primary and shadow rays, grid against brute
// force, Vulkan against the C++ reference, on a list of scenes; with --spd, the
// SPD scenes' ray counts against the published ones and their times (docs/bench.md).
// Returns the exit status; throws for errors the caller reports as "error: ...".
#include <cstdint>
#include <string>
#include <vector>

namespace vkrt::bench {

struct BenchArgs {
    std::vector<std::string> scenes;  // empty: the default list (docs/bench.md)
    std::uint32_t width = 512;
    std::uint32_t height = 512;
    std::uint32_t runs = 3;           // the median of these is reported
    std::string backend = "both";     // vulkan, cpu or both
    std::string device;
    std::string csv;                  // empty: no CSV file
    bool sweep = false;               // random spheres, 1k to 1M: cost against primitive count
    bool threshold = false;           // random spheres, 1 to 256: where the grid starts to win
    bool spd = false;                 // the SPD scenes under the SPD rules: ray counts against the published ones
    std::string spd_dir;               // where --spd finds them; empty: the source tree's scenes/spd
    bool quiet = false;
    std::string command_line;         // printed above the table, so a pasted table says how it was made
};

int run_bench(const BenchArgs& args);

}  // namespace vkrt::bench
