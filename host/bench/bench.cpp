#include "bench/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "bench/process.hpp"
#include "bench/random_spheres.hpp"
#include "bench/spd.hpp"
#include "bench/support.hpp"
#include "bench/table.hpp"
#include "app/source_tree.hpp"
#include "kernel/types.hpp"
#include "render/render.hpp"
#include "scene/limits.hpp"
#include "scene/json_scene_loader.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"

namespace vkrt::bench {
namespace {

namespace fs = std::filesystem;

// In the source tree; docs/bench.md says where each comes from.
const std::vector<std::string> kDefaultScenes = {
    "scenes/gallery/h_random_spheres.json",   "scenes/spd/balls.nff.gz",
    "scenes/spd/tetra.nff.gz",                "scenes/gallery/j_torus_knot.json",
    "scenes/bench/ten_spheres.json",          "scenes/bench/bunny_on_terrain.json",
    "scenes/bench/teapot_in_stadium.json",
};
const std::vector<std::uint64_t> kSweepCounts = {1000, 10000, 100000, 1000000};
const std::vector<std::uint64_t> kThresholdCounts = {1, 2, 4, 8, 16, 32, 64, 128, 256};

// Brute force renders at most this many pixel x primitive pairs (each eye ray tests
// every primitive, and so does each shadow ray that is not blocked early). The
// 2-core development machine's reference runs 3e7 (triangles) to 1e8 (spheres)
// tests a second, so 1e8 keeps a brute-force render within a few seconds. Larger
// scenes render brute force at a smaller image of the same view; the rates are per
// ray, so they still compare with the grid's at full size.
constexpr double kBrutePixelPrimitives = 1e8;

// The loop budget lifted for the reference's brute force, which has no lavapipe
// underneath to cut it (shaders/kernel/constants.glsl explains why the counters
// still cannot overflow at one sample per pixel).
constexpr std::uint32_t kUnlimitedLoopBudget = 0xFFFFFFFFu;

constexpr const char* kLoopBudgetNa = "n/a (loop budget)";

struct BenchScene {
    std::string label;
    Scene scene;
};

// One (backend, accel) column of a scene's measurement, filled run by run.
struct Cell {
    Backend* backend;
    bool grid;
    std::uint32_t width;
    std::uint32_t height;
    std::string not_measured;
    std::vector<RenderStats> without_shadows;
    std::vector<RenderStats> with_shadows;
};

std::uint64_t primitive_count(const Scene& s) { return s.primitive_count(); }

// The view of the full-size image, shrunk so that brute force stays within
// kBrutePixelPrimitives.
std::pair<std::uint32_t, std::uint32_t> brute_force_size(std::uint32_t width, std::uint32_t height,
                                                         std::uint64_t primitives) {
    const double pairs = double(width) * double(height) * double(std::max<std::uint64_t>(primitives, 1));
    if (pairs <= kBrutePixelPrimitives) return {width, height};
    const double scale = std::sqrt(kBrutePixelPrimitives / pairs);
    return {std::max(1u, std::uint32_t(std::lround(width * scale))),
            std::max(1u, std::uint32_t(std::lround(height * scale)))};
}

// Brute force on Vulkan runs only where one sample fits the kernel's loop budget:
// the eye ray and one shadow ray per light each loop over every primitive, plus a
// loop entry per primitive kind and two for the deferred spheres' loops. Above that
// lavapipe would cut the loops silently, so the kernel would stop the samples; the
// cell says n/a instead of running. A ray that starts near more than four spheres
// loops over the spheres once more per four (deferred_spheres.glsl), which this leaves out;
// a render that runs out anyway reports its truncated samples.
bool fits_loop_budget(const Scene& s) {
    const std::uint64_t per_query = primitive_count(s) + 6;
    return (1 + s.lights.size()) * per_query + 16 <= kernel::DEFAULT_LOOP_BUDGET;
}

void configure(Scene& s, const Cell& cell, bool shadows) {
    s.camera.width = cell.width;
    s.camera.height = cell.height;
    // One eye ray per pixel through its centre, shadows to every light and no
    // secondary rays: exactly the two ray kinds the table reports.
    s.render.spp = 1;
    s.render.aa = 1;
    s.render.jitter = false;
    s.render.max_depth = 0;
    s.render.shadows = shadows;
    s.render.grid.mode = cell.grid ? GridMode::On : GridMode::Off;
    const bool unlimited = !cell.grid && cell.backend->name() == "cpu";
    s.render.loop_budget = unlimited ? kUnlimitedLoopBudget : 0;
}

double median_of(const std::vector<RenderStats>& runs, double RenderStats::*field) {
    std::vector<double> values;
    for (const RenderStats& s : runs) values.push_back(s.*field);
    return median(values);
}

BenchRow make_row(const BenchScene& bench_scene, const Cell& cell) {
    BenchRow row;
    row.scene = bench_scene.label;
    row.primitives = primitive_count(bench_scene.scene);
    row.backend = cell.backend->name();
    row.accel = cell.grid ? "grid" : "brute";
    row.width = cell.width;
    row.height = cell.height;
    row.not_measured = cell.not_measured;
    if (!row.measured() || cell.with_shadows.empty()) return row;

    const RenderStats& off = cell.without_shadows.front();
    const RenderStats& on = cell.with_shadows.front();  // ray counts are the same in every run
    row.eye_rays = off.eye_rays;
    row.shadow_rays = on.shadow_rays;
    row.rays = on.rays();
    row.seconds_no_shadows = median_of(cell.without_shadows, &RenderStats::render_seconds);
    row.seconds = median_of(cell.with_shadows, &RenderStats::render_seconds);
    row.cells_per_ray = on.per_ray(on.cells_visited);
    row.tests_per_ray = on.per_ray(on.intersection_tests);
    row.grid_resolution = on.grid.resolution;
    row.grid_bytes = on.grid.bytes;
    std::vector<double> builds;
    for (const auto* runs : {&cell.without_shadows, &cell.with_shadows}) {
        for (const RenderStats& s : *runs) builds.push_back(s.grid.build_seconds);
    }
    row.grid_build_seconds = median(builds);
    return row;
}

class Bench {
public:
    Bench(const BenchArgs& args, const std::vector<std::unique_ptr<Backend>>& backends)
        : args_(args), backends_(backends) {}

    std::vector<BenchRow> measure(BenchScene& s) {
        std::vector<Cell> cells;
        const auto [brute_width, brute_height] = brute_force_size(args_.width, args_.height, primitive_count(s.scene));
        for (const auto& b : backends_) {
            cells.push_back(Cell{b.get(), true, args_.width, args_.height, {}, {}, {}});
            Cell brute{b.get(), false, brute_width, brute_height, {}, {}, {}};
            if (b->name() == "vulkan" && !fits_loop_budget(s.scene)) brute.not_measured = kLoopBudgetNa;
            cells.push_back(std::move(brute));
        }
        // Runs interleave the cells, so a machine that slows down for a while slows
        // every cell alike and their ratios stay meaningful.
        for (std::uint32_t run = 0; run < args_.runs; ++run) {
            for (Cell& cell : cells) {
                if (cell.not_measured.empty()) render_cell(s, cell, run);
            }
        }
        std::vector<BenchRow> rows;
        for (const Cell& cell : cells) rows.push_back(make_row(s, cell));
        return rows;
    }

private:
    void render_cell(BenchScene& s, Cell& cell, std::uint32_t run) {
        const char* accel = cell.grid ? "grid" : "brute";
        for (const bool shadows : {false, true}) {
            configure(s.scene, cell, shadows);
            RenderStats stats = render_scene(s.scene, *cell.backend).stats;
            if (stats.truncated_samples > 0) {
                cell.not_measured = kLoopBudgetNa;
                note("bench: {}: {} {}: {} samples ran out of the loop budget; not measured", s.label,
                     cell.backend->name(), accel, stats.truncated_samples);
                return;
            }
            if (cell.grid && !stats.grid.used) warn_grid_not_built(s.label, cell.backend->name(), stats.grid.reason);
            (shadows ? cell.with_shadows : cell.without_shadows).push_back(std::move(stats));
        }
        note("bench: {}: {} {} {}x{}, run {}/{}: {:.3f} s without shadows, {:.3f} s with", s.label,
             cell.backend->name(), accel, cell.width, cell.height, run + 1, args_.runs,
             cell.without_shadows.back().render_seconds, cell.with_shadows.back().render_seconds);
    }

    // A grid that was asked for but not built makes the "grid" row brute force; said
    // once per scene and backend, since every run would say the same.
    void warn_grid_not_built(const std::string& label, const std::string& backend, const std::string& reason) {
        if (!grid_warned_.insert(label + "\n" + backend).second) return;
        fmt::print(stderr, "warning: {}: the grid was not built on {}{}; its row measures brute force\n", label,
                   backend, reason.empty() ? "" : " (" + reason + ")");
    }

    template <typename... T>
    void note(fmt::format_string<T...> format, T&&... values) const {
        if (!args_.quiet) fmt::print(stderr, "{}\n", fmt::format(format, std::forward<T>(values)...));
    }

    const BenchArgs& args_;
    const std::vector<std::unique_ptr<Backend>>& backends_;
    std::set<std::string> grid_warned_;
};

BenchScene bench_scene(const std::string& label, Scene scene) {
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "warning: {}\n", warning);
    return {label, std::move(scene)};
}

BenchScene load_bench_scene(const std::string& label, const fs::path& file, bool quiet) {
    if (!quiet) fmt::print(stderr, "bench: loading {}\n", label);
    return bench_scene(label, load_scene(file));
}

// The machine and command, and how the figures were measured.
void print_header(const BenchArgs& args, const std::vector<std::unique_ptr<Backend>>& backends) {
    print_machine(args, backends);
    fmt::print("method:  1 eye ray per pixel, shadow rays to every light, no reflection or refraction; median of {} "
               "run{}; render s = the sample loop (GPU timestamps on Vulkan); brute force at most {:g} pixel x "
               "primitive pairs (docs/bench.md)\n\n",
               args.runs, args.runs == 1 ? "" : "s", kBrutePixelPrimitives);
}

// The scenes named on the command line, else the defaults from the source tree;
// every file is checked before the first render, not after minutes of benchmark.
std::vector<ProcessScene> listed_files(const BenchArgs& args) {
    const bool defaults = args.scenes.empty();
    std::vector<ProcessScene> listed;
    for (const std::string& label : defaults ? kDefaultScenes : args.scenes) {
        listed.push_back({label, defaults ? app::source_tree_path(label).string() : label});
        if (!fs::is_regular_file(listed.back().file)) {
            throw std::runtime_error(fmt::format("{}: no such scene file", listed.back().file));
        }
    }
    return listed;
}

std::vector<BenchScene> load_listed_scenes(const BenchArgs& args, const std::vector<ProcessScene>& listed) {
    std::vector<BenchScene> scenes;
    for (const ProcessScene& s : listed) scenes.push_back(load_bench_scene(s.label, s.file, args.quiet));
    return scenes;
}

// The command-to-image table: the listed scene files (with the defaults, also the
// 100,000 spheres written out as a JSON file), each rendered by its own process.
std::vector<ProcessRow> measure_command_to_image(const BenchArgs& args, std::vector<ProcessScene> scenes) {
    std::string pattern = (fs::temp_directory_path() / "vkrt-bench-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
        throw std::runtime_error(fmt::format("cannot make a directory for the command-to-image runs in {}",
                                             fs::temp_directory_path().string()));
    }
    const fs::path scratch = pattern;
    struct Remove {
        fs::path dir;
        ~Remove() {
            std::error_code ignored;
            fs::remove_all(dir, ignored);
        }
    } remove{scratch};
    if (args.scenes.empty()) {
        const fs::path spheres = scratch / "100k_spheres.json";
        std::ofstream out(spheres);
        out << explicit_spheres_json(100000);
        if (!out.flush()) throw std::runtime_error(fmt::format("{}: cannot write the scene", spheres.string()));
        scenes.push_back({"100,000 spheres, one JSON object each", spheres.string()});
    }
    ProcessPlan plan;
    plan.executable = fs::read_symlink("/proc/self/exe").string();
    if (args.backend != "cpu") plan.backends.push_back("vulkan");
    if (args.backend != "vulkan") plan.backends.push_back("cpu");
    plan.device = args.device;
    plan.runs = args.runs;
    plan.scratch = scratch.string();
    plan.quiet = args.quiet;
    return measure_processes(plan, scenes);
}

std::vector<BenchScene> generated_scenes(const std::vector<std::uint64_t>& counts, bool quiet) {
    std::vector<BenchScene> scenes;
    for (const std::uint64_t count : counts) {
        const std::string label = fmt::format("{} random sphere{}", count, count == 1 ? "" : "s");
        if (!quiet) fmt::print(stderr, "bench: generating {}\n", label);
        scenes.push_back(bench_scene(label, parse_json_scene(random_spheres_scene(count), fmt::format("{}.json", label))));
    }
    return scenes;
}

}  // namespace

int run_bench(const BenchArgs& args) {
    const auto start = std::chrono::steady_clock::now();
    if (const std::string problem = limits::image_size_problem(args.width, args.height); !problem.empty()) {
        throw SceneError("--width/--height: " + problem);
    }
    if (args.backend == "cpu" && !args.device.empty()) {
        fmt::print(stderr, "warning: --device applies to the vulkan backend only; ignored\n");
    }
    if (args.spd) return run_spd_bench(args);
    // Scene files first (seconds at most, and where most mistakes are), then the
    // CSV file and the devices: every mistake fails before the benchmark, not after.
    const bool listed = (!args.sweep && !args.threshold) || !args.scenes.empty();
    const std::vector<ProcessScene> files = listed ? listed_files(args) : std::vector<ProcessScene>{};
    std::vector<BenchScene> scenes = load_listed_scenes(args, files);
    std::vector<BenchScene> sweep = args.sweep ? generated_scenes(kSweepCounts, args.quiet) : std::vector<BenchScene>{};
    std::vector<BenchScene> threshold =
        args.threshold ? generated_scenes(kThresholdCounts, args.quiet) : std::vector<BenchScene>{};
    std::ofstream csv;
    if (!args.csv.empty()) {
        csv.open(args.csv);
        if (!csv) throw std::runtime_error(fmt::format("{}: cannot write the CSV file", args.csv));
    }
    const std::vector<std::unique_ptr<Backend>> backends = make_backends(args);
    print_header(args, backends);

    Bench bench(args, backends);
    std::vector<BenchRow> all;
    auto run_group = [&](const char* title, std::vector<BenchScene>& group) {
        if (group.empty()) return std::vector<BenchRow>{};
        std::vector<BenchRow> rows;
        for (BenchScene& s : group) {
            std::vector<BenchRow> scene_rows = bench.measure(s);
            rows.insert(rows.end(), scene_rows.begin(), scene_rows.end());
        }
        compare_rows(rows);
        std::ostringstream table;
        write_markdown(table, rows);
        fmt::print("{}\n\n{}\n", title, table.str());
        std::fflush(stdout);
        all.insert(all.end(), rows.begin(), rows.end());
        return rows;
    };
    run_group("Scenes", scenes);
    if (!files.empty()) {
        std::ostringstream table;
        write_process_markdown(table, measure_command_to_image(args, files));
        fmt::print("Command to image: `vkrt render SCENE`, one process per run, as the scene asks "
                   "(docs/bench.md#command-to-image)\n\n{}\n", table.str());
        std::fflush(stdout);
    }
    run_group("Cost against primitive count (random spheres)", sweep);
    const std::vector<BenchRow> threshold_rows = run_group("Grid against brute force on few primitives", threshold);
    if (!threshold_rows.empty()) {
        fmt::print("Where the grid starts to win (rays/s with shadows, all rays):\n");
        for (const std::string& line : threshold_summary(threshold_rows)) fmt::print("- {}\n", line);
        fmt::print("\n");
    }

    if (csv.is_open()) {
        write_csv(csv, all);
        csv.close();
        if (!csv) throw std::runtime_error(fmt::format("{}: cannot write the CSV file", args.csv));
    }
    if (!args.quiet) {
        fmt::print(stderr, "bench: done in {:.0f} s\n",
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return 0;
}

}  // namespace vkrt::bench
