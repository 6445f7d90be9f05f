// `vkrt bench` through the real program, at sizes that take seconds: that its CSV
// has one row per (backend, accel) with positive rates, that the table carries the
// machine it was measured on, and that its mistakes are one-line errors; and that
// `vkrt bench --spd` puts the published SPD counts beside the counts it measured.
// Whether the figures are fast enough is the benchmark's business, not a test's.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
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
        EXPECT_EQ(row.at("primitives"), "11") << cell;  // ten spheres and a quad
        // Eleven primitives is far below the brute-force budget: full size everywhere.
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
                              "| 11 | cpu | brute | 32x24 |", "Command to image",
                              "| scene | backend | whole process s | load s | set-up s | render s | peak MiB |"}) {
        EXPECT_NE(table.find(piece), std::string::npos) << piece << " not in:\n" << table;
    }
    EXPECT_NE(run.stderr_text.find("run 1/1"), std::string::npos) << "no progress lines:\n" << run.stderr_text;
    // One command-to-image row per backend, each with figures: the renders ran as
    // separate processes and their stats were read back.
    for (const char* backend : {"vulkan", "cpu"}) {
        const std::string start = "ten_spheres.json | " + std::string(backend) + " | ";
        const auto at = table.find(start);
        ASSERT_NE(at, std::string::npos) << start << " not in:\n" << table;
        const std::string row = table.substr(at + start.size(), table.find('\n', at) - at - start.size());
        const std::vector<std::string> fields = split(row, '|');
        ASSERT_GE(fields.size(), 5u) << row;
        EXPECT_GT(std::stod(fields[0]), 0.0) << row;   // whole process
        EXPECT_GT(std::stod(fields[3]), 0.0) << row;   // render
        EXPECT_GE(std::stod(fields[4]), 10.0) << row;  // peak MiB: at least the program itself
    }
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

// The default scene list lives in the source tree: bench finds it from any directory.
TEST(Bench, DefaultScenesComeFromTheRepo) {
    const fs::path dir = test::temp_dir("bench_defaults");
    const fs::path csv = dir / "defaults.csv";
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    const test::ProgramRun run = test::run_vkrt(
        "bench -q --backend cpu --runs 1 --width 16 --height 16 --csv " + test::shell_quote(csv.string()), dir);
    fs::current_path(previous);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    std::string header;
    std::set<std::string> scenes;
    for (const auto& row : read_csv(csv, header)) {
        EXPECT_EQ(row.at("status"), "ok") << row.at("scene");
        scenes.insert(row.at("scene"));
    }
    EXPECT_EQ(scenes, (std::set<std::string>{"scenes/gallery/h_random_spheres.json", "scenes/spd/balls.nff.gz",
                                             "scenes/spd/tetra.nff.gz", "scenes/gallery/j_torus_knot.json",
                                             "scenes/bench/ten_spheres.json", "scenes/bench/bunny_on_terrain.json",
                                             "scenes/bench/teapot_in_stadium.json"}));
}

// ---- --spd -----------------------------------------------------------------------

// A square that fills the whole view of an 8 x 8 image, facing the eye and the
// light: each of the 9 x 9 corner rays hits it and casts one shadow ray. With Ks > 0
// each also spawns a reflection ray, which goes back past the eye and hits nothing.
std::string square_nff(double ks) {
    std::ostringstream text;
    text << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 8 8\n"
            "b 0.1 0.2 0.3\n"
            "l 0 0 10\n"
            "f 0.8 0.8 0.8 1 "
         << ks
         << " 20 0 0\n"
            "p 4\n-10 -10 0\n10 -10 0\n10 10 0\n-10 10 0\n";
    return text.str();
}

const std::string kSpdHeader =
    "scene,primitives,backend,width,height,eye_rays,eye_hits,eye_hits_published,eye_hits_diff_pct,reflection_rays,"
    "reflection_rays_published,reflection_rays_diff_pct,refraction_rays,refraction_rays_published,"
    "refraction_rays_diff_pct,shadow_rays,shadow_rays_published,shadow_rays_diff_pct,within_10pct,dropped_rays,"
    "truncated_samples,counts_identical,load_s,flatten_s,grid_build_s,setup_s,preprocess_s,render_s,rays,"
    "mrays_per_s";

// The Markdown table's rows (after the header and separator lines), as cells.
std::vector<std::vector<std::string>> markdown_rows(const std::string& text, std::string& header) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream in(text);
    bool in_table = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("| scene |", 0) == 0) {
            header = line;
            in_table = true;
            continue;
        }
        if (!in_table || line.rfind("|---", 0) == 0) continue;
        if (line.empty() || line[0] != '|') break;
        std::vector<std::string> cells;
        for (std::string cell : split(line.substr(1, line.size() - 2), '|')) {
            cells.push_back(cell.substr(1, cell.size() - 2));  // the spaces around each cell
        }
        rows.push_back(cells);
    }
    return rows;
}

// Two tiny NFF files: "tetra.nff", which the published table has a row for (so its
// published columns must be SPD tetra's and the differences computed against them),
// and "mirror.nff.gz", which it has not, gzipped as the repo's SPD scenes are.
fs::path write_spd_dir(const fs::path& dir) {
    const fs::path spd = dir / "spd";
    fs::create_directories(spd);
    std::ofstream(spd / "tetra.nff") << square_nff(0.0);
    test::write_gzip(spd / "mirror.nff.gz", square_nff(0.5));
    std::ofstream(spd / "notes.txt") << "not a scene: --spd reads .nff files only\n";
    return spd;
}

TEST(BenchSpd, CountsBesideThePublishedTable) {
    const fs::path dir = test::temp_dir("bench_spd");
    const fs::path spd = write_spd_dir(dir);
    const fs::path csv = dir / "spd.csv";
    const test::ProgramRun run = test::run_vkrt("bench --spd --spd-dir " + test::shell_quote(spd.string()) +
                                                    " --runs 2 --csv " + test::shell_quote(csv.string()),
                                                dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;

    const std::string out = read_file(dir / "stdout.txt");
    for (const char* piece : {"machine: ", "vulkan:  llvmpipe", "command: ", "method:  the SPD test rules"}) {
        EXPECT_NE(out.find(piece), std::string::npos) << piece << " not in:\n" << out;
    }
    std::string header;
    const auto rows = markdown_rows(out, header);
    EXPECT_EQ(header,
              "| scene | primitives | backend | eye hits | published | diff | reflection | published | diff "
              "| refraction | published | diff | shadow | published | diff | within 10% | preprocess s "
              "| ray-trace s | Mrays/s |");
    // Files by name, backends in --backend both's order.
    ASSERT_EQ(rows.size(), 4u) << out;
    const std::vector<std::pair<std::string, std::string>> order = {
        {"mirror", "vulkan"}, {"mirror", "cpu"}, {"tetra", "vulkan"}, {"tetra", "cpu"}};
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const std::vector<std::string>& r = rows[i];
        ASSERT_EQ(r.size(), 19u) << out;
        EXPECT_EQ(r[0], order[i].first);
        EXPECT_EQ(r[2], order[i].second);
        EXPECT_EQ(r[1], "2");     // the square's two triangles
        EXPECT_EQ(r[3], "81");    // 9 x 9 corner rays, all hit
        EXPECT_EQ(r[12], "81");   // one shadow ray each
        EXPECT_EQ(r[9], "0");     // no glass
        EXPECT_GT(std::stod(r[17]), 0.0) << "ray-trace seconds";
        EXPECT_GT(std::stod(r[18]), 0.0) << "Mrays/s";
        if (r[0] == "mirror") {
            EXPECT_EQ(r[6], "81");  // a reflection ray from every hit: Ks > 0
            for (std::size_t c : {4u, 5u, 7u, 8u, 10u, 11u, 13u, 14u, 15u}) EXPECT_EQ(r[c], "–") << "column " << c;
        } else {
            EXPECT_EQ(r[6], "0");
            // SPD tetra's published counts: 49,788 eye rays that hit, no secondary
            // rays, 46,112 shadow rays; the differences are against those.
            EXPECT_EQ(r[4], "49,788");
            EXPECT_EQ(r[5], "-99.8%");  // 81 / 49,788 - 1
            EXPECT_EQ(r[7], "0");
            EXPECT_EQ(r[8], "0.0%");
            EXPECT_EQ(r[10], "0");
            EXPECT_EQ(r[11], "0.0%");
            EXPECT_EQ(r[13], "46,112");
            EXPECT_EQ(r[14], "-99.8%");
            EXPECT_EQ(r[15], "no: eye hits, shadow");
        }
    }
    EXPECT_NE(out.find("More than 10% off the published count: tetra vulkan eye hits; tetra vulkan shadow; "
                       "tetra cpu eye hits; tetra cpu shadow."),
              std::string::npos)
        << out;

    std::string csv_header;
    const auto csv_rows = read_csv(csv, csv_header);
    EXPECT_EQ(csv_header, kSpdHeader);
    ASSERT_EQ(csv_rows.size(), 4u);
    for (const auto& row : csv_rows) {
        const std::string cell = row.at("scene") + " " + row.at("backend");
        EXPECT_EQ(row.at("width") + "x" + row.at("height"), "8x8") << cell;
        EXPECT_EQ(row.at("eye_rays"), "81") << cell;
        EXPECT_EQ(row.at("counts_identical"), "yes") << cell;
        EXPECT_EQ(row.at("dropped_rays"), "0") << cell;
        EXPECT_EQ(row.at("truncated_samples"), "0") << cell;
        EXPECT_EQ(row.at("rays"), row.at("scene") == "mirror" ? "243" : "162") << cell;
        // Preprocessing is the sum of its parts, each the median of 2 runs; the sum's
        // median is not the medians' sum, but with two runs both are averages.
        const double parts = std::stod(row.at("load_s")) + std::stod(row.at("flatten_s")) +
                             std::stod(row.at("setup_s"));
        EXPECT_NEAR(std::stod(row.at("preprocess_s")), parts, 1e-9) << cell;
        EXPECT_LE(std::stod(row.at("grid_build_s")), std::stod(row.at("flatten_s"))) << cell;
        if (row.at("scene") == "tetra") {
            EXPECT_EQ(row.at("shadow_rays_published"), "46112") << cell;
            EXPECT_NEAR(std::stod(row.at("shadow_rays_diff_pct")), 100.0 * (81.0 / 46112.0 - 1.0), 1e-9) << cell;
            EXPECT_EQ(row.at("within_10pct"), "no") << cell;
        } else {
            EXPECT_EQ(row.at("shadow_rays_published"), "") << cell;
            EXPECT_EQ(row.at("within_10pct"), "") << cell;
        }
    }
    EXPECT_NE(run.stderr_text.find("tetra: cpu run 2/2"), std::string::npos) << run.stderr_text;
}

TEST(BenchSpd, MistakesAreOneLineErrors) {
    const fs::path dir = test::temp_dir("bench_spd_errors");
    const fs::path spd = write_spd_dir(dir);
    const std::string spd_dir = " --spd-dir " + test::shell_quote(spd.string());
    expect_one_error("bench --spd --spd-dir " + test::shell_quote((dir / "nowhere").string()),
                     {"nowhere", "no such directory", "--spd-dir"}, dir);
    const fs::path empty = dir / "empty";
    fs::create_directories(empty);
    expect_one_error("bench --spd --spd-dir " + test::shell_quote(empty.string()), {"empty", "no .nff files"}, dir);
    expect_one_error("bench --spd-dir " + test::shell_quote(spd.string()), {"--spd-dir", "--spd"}, dir);
    expect_one_error("bench --spd --scene " + ten_spheres() + spd_dir, {"--spd", "--scene"}, dir);
    expect_one_error("bench --spd --width 64" + spd_dir, {"--spd", "--width"}, dir);
    expect_one_error("bench --spd --sweep" + spd_dir, {"--spd", "--sweep"}, dir);
    expect_one_error("bench --spd --csv /nonexistent/dir/s.csv" + spd_dir,
                     {"/nonexistent/dir/s.csv", "cannot write the CSV file"}, dir);
    std::ofstream(spd / "broken.nff") << "s 0 0\n";
    expect_one_error("bench --spd -q" + spd_dir, {"broken.nff", "'s'"}, dir);
}

// Without --spd-dir, --spd renders the ten SPD scenes the repo carries, from any
// working directory, and the seven with published counts land within their 10%.
TEST(BenchSpd, DefaultDirectoryIsTheReposScenes) {
    const fs::path dir = test::temp_dir("bench_spd_default");
    const fs::path csv = dir / "spd.csv";
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    const test::ProgramRun run =
        test::run_vkrt("bench --spd --backend cpu --runs 1 -q --csv " + test::shell_quote(csv.string()), dir);
    fs::current_path(previous);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    std::string header;
    const auto rows = read_csv(csv, header);
    std::vector<std::string> names;
    for (const auto& row : rows) {
        names.push_back(row.at("scene"));
        const bool published = row.at("scene") != "jacks" && row.at("scene") != "lattice" && row.at("scene") != "shells";
        EXPECT_EQ(row.at("within_10pct"), published ? "yes" : "") << row.at("scene");
    }
    EXPECT_EQ(names, (std::vector<std::string>{"balls", "gears", "jacks", "lattice", "mount", "rings", "shells",
                                                "teapot", "tetra", "tree"}));
}

}  // namespace
