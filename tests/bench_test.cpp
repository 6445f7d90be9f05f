// `vkrt bench` through the real program, at sizes that take seconds: that its CSV
// has one row per (backend, accel) with positive rates, that the table carries the
// machine it was measured on, and that its mistakes are one-line errors. Whether
// the figures are fast enough is the benchmark's business, not a test's.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

const std::string kHeader =
    "scene,primitives,backend,accel,width,height,status,eye_rays,shadow_rays,rays,render_s_no_shadows,render_s,"
    "primary_mrays_per_s,shadow_mrays_per_s,mrays_per_s,cells_per_ray,tests_per_ray,grid_resolution,grid_build_s,"
    "grid_bytes,grid_speedup,grid_speedup_baseline,vulkan_vs_cpu";

std::string read_file(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator)) parts.push_back(part);
    if (!text.empty() && text.back() == separator) parts.push_back("");
    return parts;
}

// The CSV's rows as column name -> value (no field of these rows needs quoting).
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file, std::string& header) {
    std::istringstream in(read_file(file));
    std::getline(in, header);
    const std::vector<std::string> names = split(header, ',');
    std::vector<std::map<std::string, std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        const std::vector<std::string> values = split(line, ',');
        EXPECT_EQ(values.size(), names.size()) << line;
        std::map<std::string, std::string>& row = rows.emplace_back();
        for (std::size_t i = 0; i < names.size() && i < values.size(); ++i) row[names[i]] = values[i];
    }
    return rows;
}

std::string ten_spheres() {
    return test::shell_quote((test::source_dir() / "scenes" / "bench" / "ten_spheres.json").string());
}

TEST(Bench, BothBackendsGridAndBruteForce) {
    const fs::path dir = test::temp_dir("bench_both");
    const fs::path csv = dir / "bench.csv";
    const test::ProgramRun run = test::run_vkrt(
        "bench --scene " + ten_spheres() + " --width 32 --height 24 --runs 1 --csv " + test::shell_quote(csv.string()),
        dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;

    std::string header;
    const auto rows = read_csv(csv, header);
    EXPECT_EQ(header, kHeader);
    std::set<std::string> cells;
    for (const auto& row : rows) {
        const std::string cell = row.at("backend") + " " + row.at("accel");
        EXPECT_TRUE(cells.insert(cell).second) << "two rows for " << cell;
        EXPECT_EQ(row.at("status"), "ok") << cell;
        EXPECT_EQ(row.at("primitives"), "12") << cell;  // ten spheres and a quad's two triangles
        // Twelve primitives is far below the brute-force budget: full size everywhere.
        EXPECT_EQ(row.at("width") + "x" + row.at("height"), "32x24") << cell;
        EXPECT_EQ(row.at("eye_rays"), "768") << cell;
        EXPECT_GT(std::stoull(row.at("shadow_rays")), 0u) << cell;
        EXPECT_GT(std::stod(row.at("primary_mrays_per_s")), 0.0) << cell;
        EXPECT_GT(std::stod(row.at("mrays_per_s")), 0.0) << cell;
        // Shadow rays are timed as a difference of two renders; on an image this small
        // the difference may drown in noise, and then the field is left empty rather
        // than negative.
        if (!row.at("shadow_mrays_per_s").empty()) {
            EXPECT_GT(std::stod(row.at("shadow_mrays_per_s")), 0.0) << cell;
        }
    }
    EXPECT_EQ(cells, (std::set<std::string>{"vulkan grid", "vulkan brute", "cpu grid", "cpu brute"}));
    for (const auto& row : rows) {
        if (row.at("accel") == "grid") {
            EXPECT_GT(std::stod(row.at("grid_speedup")), 0.0) << row.at("backend");
        }
        if (row.at("backend") == "vulkan") {
            EXPECT_GT(std::stod(row.at("vulkan_vs_cpu")), 0.0) << row.at("accel");
        }
    }

    const std::string table = read_file(dir / "stdout.txt");
    for (const char* piece : {"machine: ", "vulkan:  llvmpipe", "command: ", "| scene | primitives | backend | accel",
                              "| 12 | cpu | brute | 32x24 |"}) {
        EXPECT_NE(table.find(piece), std::string::npos) << piece << " not in:\n" << table;
    }
    EXPECT_NE(run.stderr_text.find("run 1/1"), std::string::npos) << "no progress lines:\n" << run.stderr_text;
}

TEST(Bench, OneBackendAndQuiet) {
    const fs::path dir = test::temp_dir("bench_cpu");
    const fs::path csv = dir / "bench.csv";
    const test::ProgramRun run = test::run_vkrt("bench --scene " + ten_spheres() +
                                                    " --width 16 --height 16 --runs 2 --backend cpu -q --csv " +
                                                    test::shell_quote(csv.string()),
                                                dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    std::string header;
    const auto rows = read_csv(csv, header);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].at("backend"), "cpu");
    EXPECT_EQ(rows[1].at("backend"), "cpu");
    EXPECT_EQ(run.stderr_text, "");
    EXPECT_EQ(read_file(dir / "stdout.txt").find("vulkan:"), std::string::npos);
}

// Every mistake is found before the first render and reported as one line; the
// progress lines ("bench: loading ...") may come before it.
void expect_one_error(const std::string& args, const std::vector<std::string>& pieces, const fs::path& dir) {
    const test::ProgramRun run = test::run_vkrt(args, dir);
    EXPECT_EQ(run.code, 1) << args;
    std::vector<std::string> lines;
    for (const std::string& line : split(run.stderr_text, '\n')) {
        if (!line.empty() && line.rfind("bench: ", 0) != 0) lines.push_back(line);
    }
    ASSERT_EQ(lines.size(), 1u) << "expected one error line from: " << args << "\n" << run.stderr_text;
    EXPECT_EQ(lines[0].rfind("error: ", 0), 0u) << lines[0];
    EXPECT_EQ(run.stderr_text.back(), '\n');
    for (const std::string& piece : pieces) {
        EXPECT_NE(lines[0].find(piece), std::string::npos) << "missing '" << piece << "' in: " << lines[0];
    }
}

TEST(Bench, MistakesAreOneLineErrors) {
    const fs::path dir = test::temp_dir("bench_errors");
    const std::string scene = " --scene " + ten_spheres();
    expect_one_error("bench --scene no_such_scene.json -q", {"no_such_scene.json", "no such scene file"}, dir);
    expect_one_error("bench" + scene + " --runs 0", {"--runs", "whole number from 1", "'0'"}, dir);
    expect_one_error("bench" + scene + " --width 16 --height 16 --csv /nonexistent/dir/b.csv",
                     {"/nonexistent/dir/b.csv", "cannot write the CSV file"}, dir);
    expect_one_error("bench" + scene + " --backend gpu", {"--backend", "gpu"}, dir);
    expect_one_error("bench" + scene + " --width 32768 --height 32768", {"--width/--height", "limit"}, dir);
    const std::string bad_scene = (dir / "bad.json").string();
    std::ofstream(bad_scene) << "{\"camera\": 1}";
    expect_one_error("bench --scene " + test::shell_quote(bad_scene), {"bad.json", "camera"}, dir);
}

// The default scene list is named relative to the repo root; elsewhere the error
// says so instead of just "no such file".
TEST(Bench, DefaultScenesNeedTheRepoRoot) {
    const fs::path dir = test::temp_dir("bench_defaults");
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    const test::ProgramRun run = test::run_vkrt("bench -q", dir);
    fs::current_path(previous);
    EXPECT_EQ(run.code, 1);
    EXPECT_NE(run.stderr_text.find("no such scene file"), std::string::npos) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("repo root"), std::string::npos) << run.stderr_text;
}

}  // namespace
