#pragma once
// The rows `vkrt bench` measures and the forms it writes them in: a Markdown table
// for the terminal and the README, CSV for scripts, and the grid-threshold summary.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vkrt::bench {

// One (scene, backend, accel) measurement: medians over the runs.
struct BenchRow {
    std::string scene;
    std::uint64_t primitives = 0;  // spheres + triangles + rings + cylinders
    std::string backend;           // "vulkan" or "cpu"
    std::string accel;             // "grid" or "brute"
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::string not_measured;      // non-empty: why there are no figures, e.g. "n/a (loop budget)"

    std::uint64_t eye_rays = 0;
    std::uint64_t shadow_rays = 0;
    std::uint64_t rays = 0;               // every ray of the render with shadows
    double seconds_no_shadows = 0.0;      // median render seconds, eye rays only
    double seconds = 0.0;                 // median render seconds, eye and shadow rays
    double cells_per_ray = 0.0;
    double tests_per_ray = 0.0;
    std::array<std::uint32_t, 3> grid_resolution{0, 0, 0};
    double grid_build_seconds = 0.0;
    std::size_t grid_bytes = 0;

    // Filled by compare_rows.
    std::optional<double> speedup;        // grid rays/s over brute force rays/s
    std::string speedup_baseline;         // the backend whose brute force that was
    std::optional<double> vulkan_vs_cpu;  // vulkan rays/s over cpu rays/s, same scene and accel

    bool measured() const { return not_measured.empty(); }
    double rays_per_second() const;       // all rays, render with shadows
    double primary_rays_per_second() const;
    // shadow rays / (seconds - seconds_no_shadows); none when that difference is
    // not positive (timing noise on a scene whose shadow rays cost next to nothing).
    std::optional<double> shadow_rays_per_second() const;
};

// Fills speedup (on grid rows, against brute force on the same backend, else on
// the cpu backend when that one could not run brute force) and vulkan_vs_cpu.
void compare_rows(std::vector<BenchRow>& rows);

void write_markdown(std::ostream& out, const std::vector<BenchRow>& rows);
void write_csv(std::ostream& out, const std::vector<BenchRow>& rows);

// For each backend, the smallest primitive count from which the grid beats brute
// force at every larger count measured, as one line each; rows from --threshold.
std::vector<std::string> threshold_summary(const std::vector<BenchRow>& rows);

}  // namespace vkrt::bench
