#include "bench/spd.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "bench/spd_table.hpp"
#include "bench/support.hpp"
#include "render/render.hpp"
#include "app/source_tree.hpp"
#include "scene/load_scene.hpp"
#include "scene/read_text.hpp"

namespace vkrt::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// One run of one (scene, backend) cell. The file is loaded anew in every run, so
// that its loading is timed like the rest of the preprocessing.
struct SpdRun {
    double load_seconds = 0.0;
    RenderStats stats;
};

struct SpdCell {
    Backend* backend;
    std::vector<SpdRun> runs;
};

struct SpdScene {
    std::string name;  // the file's stem, which names its published row
    fs::path file;
    std::uint64_t primitives = 0;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<SpdCell> cells;
};

// Every .nff or .nff.gz file in the directory, by name. A missing directory or one
// without SPD files is an error before anything renders.
std::vector<fs::path> find_spd_files(const BenchArgs& args) {
    const fs::path dir = args.spd_dir.empty() ? app::source_tree_path("scenes/spd") : fs::path(args.spd_dir);
    std::error_code error;
    if (!fs::is_directory(dir, error)) {
        throw std::runtime_error(args.spd_dir.empty()
                                     ? fmt::format("{}: no such directory (the SPD scenes of the source tree vkrt was "
                                                   "built from; point --spd-dir at them)",
                                                   dir.string())
                                     : fmt::format("{}: no such directory (--spd-dir)", dir.string()));
    }
    std::vector<fs::path> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
        if (entry.is_regular_file() && format_extension(entry.path()) == ".nff") files.push_back(entry.path());
    }
    if (files.empty()) throw std::runtime_error(fmt::format("{}: no .nff files in this directory", dir.string()));
    std::sort(files.begin(), files.end());
    return files;
}

SpdCounts counts_of(const RenderStats& s) {
    return {s.eye_hits, s.reflection_rays, s.refraction_rays, s.shadow_rays};
}

// Everything a run counts; runs of one cell must agree on all of it.
std::array<std::uint64_t, 7> all_counts(const RenderStats& s) {
    return {s.eye_rays,    s.eye_hits,           s.reflection_rays,   s.refraction_rays,
            s.shadow_rays, s.dropped_low_weight + s.dropped_stack_full, s.truncated_samples};
}

SpdRow make_row(const SpdScene& scene, const SpdCell& cell) {
    SpdRow row;
    row.scene = scene.name;
    row.primitives = scene.primitives;
    row.backend = cell.backend->name();
    row.width = scene.width;
    row.height = scene.height;
    if (const SpdPublished* p = find_spd_published(scene.name)) row.published = p->counts;

    const RenderStats& first = cell.runs.front().stats;
    row.eye_rays = first.eye_rays;
    row.counts = counts_of(first);
    row.dropped_rays = first.dropped_low_weight + first.dropped_stack_full;
    row.truncated_samples = first.truncated_samples;

    std::vector<double> load, flatten, grid, setup, preprocess, render;
    for (const SpdRun& run : cell.runs) {
        const RenderStats& s = run.stats;
        if (all_counts(s) != all_counts(first)) row.counts_identical = false;
        load.push_back(run.load_seconds);
        flatten.push_back(s.flatten_seconds);
        grid.push_back(s.grid.build_seconds);
        setup.push_back(s.setup_seconds);
        preprocess.push_back(run.load_seconds + s.flatten_seconds + s.setup_seconds);
        render.push_back(s.render_seconds);
    }
    row.load_seconds = median(load);
    row.flatten_seconds = median(flatten);
    row.grid_build_seconds = median(grid);
    row.setup_seconds = median(setup);
    // The median of the runs' sums, not the sum of the parts' medians: one run's
    // preprocessing, as it happened.
    row.preprocess_seconds = median(preprocess);
    row.render_seconds = median(render);
    return row;
}

class SpdBench {
public:
    SpdBench(const BenchArgs& args, const std::vector<std::unique_ptr<Backend>>& backends)
        : args_(args), backends_(backends) {}

    // Loads every file once, before anything renders: a broken file fails the
    // benchmark at once, and its warnings are said once.
    std::vector<SpdScene> load(const std::vector<fs::path>& files) const {
        std::vector<SpdScene> scenes;
        for (const fs::path& file : files) {
            note("bench: loading {}", file.string());
            const Scene s = load_scene(file);
            for (const std::string& warning : s.warnings) fmt::print(stderr, "warning: {}\n", warning);
            SpdScene scene{scene_stem(file), file, s.primitive_count(), s.camera.width, s.camera.height, {}};
            for (const auto& b : backends_) scene.cells.push_back(SpdCell{b.get(), {}});
            scenes.push_back(std::move(scene));
        }
        return scenes;
    }

    // Runs interleave the backends, so a machine that slows down for a while slows
    // both alike.
    std::vector<SpdRow> measure(SpdScene& scene) const {
        for (std::uint32_t run = 0; run < args_.runs; ++run) {
            for (SpdCell& cell : scene.cells) cell.runs.push_back(render_once(scene, cell, run));
        }
        std::vector<SpdRow> rows;
        for (const SpdCell& cell : scene.cells) rows.push_back(make_row(scene, cell));
        return rows;
    }

private:
    SpdRun render_once(const SpdScene& scene, const SpdCell& cell, std::uint32_t run) const {
        const auto start = Clock::now();
        const Scene s = load_scene(scene.file);
        SpdRun result;
        result.load_seconds = std::chrono::duration<double>(Clock::now() - start).count();
        result.stats = render_scene(s, *cell.backend).stats;
        const RenderStats& st = result.stats;
        note("bench: {}: {} run {}/{}: preprocess {:.3f} s (load {:.3f}, flatten {:.3f}, set-up {:.3f}), ray-trace "
             "{:.3f} s",
             scene.name, cell.backend->name(), run + 1, args_.runs,
             result.load_seconds + st.flatten_seconds + st.setup_seconds, result.load_seconds, st.flatten_seconds,
             st.setup_seconds, st.render_seconds);
        return result;
    }

    template <typename... T>
    void note(fmt::format_string<T...> format, T&&... values) const {
        if (!args_.quiet) fmt::print(stderr, "{}\n", fmt::format(format, std::forward<T>(values)...));
    }

    const BenchArgs& args_;
    const std::vector<std::unique_ptr<Backend>>& backends_;
};

void print_method(const BenchArgs& args) {
    fmt::print("method:  the SPD test rules, as loading an .nff sets them (rays through the (w+1) x (h+1) pixel "
               "corners, four averaged per pixel; ray-tree depth 5; nothing pruned); counts from run 1, checked "
               "identical in every run; times the median of {} run{}; preprocess s = load + flatten (grid build "
               "included) + backend set-up; ray-trace s = the sample loop (GPU timestamps on Vulkan); published: "
               "Haines' table (docs/bench.md)\n\n",
               args.runs, args.runs == 1 ? "" : "s");
}

// After the table: which counts are more than 10% off, and what should not happen.
void print_findings(const std::vector<SpdRow>& rows) {
    std::vector<std::string> outside;
    for (const SpdRow& r : rows) {
        for (const std::string& kind : r.kinds_outside_10_percent()) {
            outside.push_back(fmt::format("{} {} {}", r.scene, r.backend, kind));
        }
    }
    const bool any_published = std::any_of(rows.begin(), rows.end(), [](const SpdRow& r) { return r.published; });
    if (!any_published) {
        fmt::print("No scene measured has a published row.\n");
    } else if (outside.empty()) {
        fmt::print("Every count of every scene with a published row is within 10% of it, on every backend measured.\n");
    } else {
        std::string list;
        for (const std::string& o : outside) list += (list.empty() ? "" : "; ") + o;
        fmt::print("More than 10% off the published count: {}.\n", list);
    }
    for (const SpdRow& r : rows) {
        if (r.dropped_rays > 0 || r.truncated_samples > 0) {
            fmt::print("{} {}: {} secondary rays dropped and {} samples truncated by the loop budget; the SPD rules "
                       "drop none, so these counts are short.\n",
                       r.scene, r.backend, r.dropped_rays, r.truncated_samples);
        }
    }
    fmt::print("\n");
}

}  // namespace

int run_spd_bench(const BenchArgs& args) {
    const auto start = Clock::now();
    // Files first, then the CSV file and the devices: every mistake fails before the
    // benchmark, not after.
    const std::vector<fs::path> files = find_spd_files(args);
    std::ofstream csv;
    if (!args.csv.empty()) {
        csv.open(args.csv);
        if (!csv) throw std::runtime_error(fmt::format("{}: cannot write the CSV file", args.csv));
    }
    const std::vector<std::unique_ptr<Backend>> backends = make_backends(args);
    const SpdBench bench(args, backends);
    std::vector<SpdScene> scenes = bench.load(files);

    print_machine(args, backends);
    print_method(args);
    std::fflush(stdout);

    std::vector<SpdRow> rows;
    for (SpdScene& scene : scenes) {
        std::vector<SpdRow> scene_rows = bench.measure(scene);
        rows.insert(rows.end(), scene_rows.begin(), scene_rows.end());
    }
    std::ostringstream table;
    write_spd_markdown(table, rows);
    fmt::print("SPD scenes\n\n{}\n", table.str());
    print_findings(rows);
    std::fflush(stdout);

    if (csv.is_open()) {
        write_spd_csv(csv, rows);
        csv.close();
        if (!csv) throw std::runtime_error(fmt::format("{}: cannot write the CSV file", args.csv));
    }
    if (!args.quiet) {
        fmt::print(stderr, "bench: done in {:.0f} s\n", std::chrono::duration<double>(Clock::now() - start).count());
    }
    // The renders are deterministic: counts that differ between runs are a bug, and
    // a benchmark that hid it would publish one run's counts as the scene's.
    int status = 0;
    for (const SpdRow& r : rows) {
        if (r.counts_identical) continue;
        fmt::print(stderr, "error: {} on {}: the ray counts differ between runs, which a deterministic render "
                           "never does; the table shows run 1's\n",
                   r.scene, r.backend);
        status = 1;
    }
    return status;
}

}  // namespace vkrt::bench
