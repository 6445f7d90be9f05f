// vkrt converge through the real program, on a small local-mode scene with jitter:
// the CSV's columns and rows per curve, the error figures against a render of the
// same samples, the reference it renders itself, the plot, and its mistakes; and
// on the global-mode room, that the estimator specs reach the kernel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "image/error_metrics.hpp"
#include "image/image.hpp"
#include "render/partial_file.hpp"
#include "render/sample_ranges.hpp"
#include "scene/limits.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

std::string q(const fs::path& p) { return test::shell_quote(p.string()); }

const std::string kScene = q(test::source_dir() / "scenes" / "spheres_triangles.json");
const std::string kHeader = "backend,estimator,spp,seconds,rmse,relmse,mean,mean_diff";

struct CsvRow {
    std::string backend, estimator;
    std::uint32_t spp = 0;
    double seconds = 0, rmse = 0, relmse = 0, mean = 0, mean_diff = 0;
};

// The rows of a converge CSV; fails the test when the header or a row is malformed.
std::vector<CsvRow> read_csv(const fs::path& file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, kHeader);
    std::vector<CsvRow> rows;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::istringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
        if (cells.size() != 8u) {
            ADD_FAILURE() << "row of " << cells.size() << " cells: " << line;
            continue;
        }
        rows.push_back({cells[0], cells[1], std::uint32_t(std::stoul(cells[2])), std::stod(cells[3]),
                        std::stod(cells[4]), std::stod(cells[5]), std::stod(cells[6]), std::stod(cells[7])});
    }
    return rows;
}

// Rows grouped by curve, in file order.
std::map<std::string, std::vector<CsvRow>> by_curve(const std::vector<CsvRow>& rows) {
    std::map<std::string, std::vector<CsvRow>> out;
    for (const CsvRow& r : rows) out[r.backend + "/" + r.estimator].push_back(r);
    return out;
}

bool gnuplot_installed() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

// Two backends, 4 spp: checkpoints 1, 2 and 4 on each, times that grow, finite
// errors; the reference rendered here is saved beside the CSV as a partial file;
// the plot is drawn when gnuplot is there (scripts/setup installs it).
TEST(Converge, OneCurvePerBackendWithCheckpointsAtPowersOfTwo) {
    const fs::path dir = test::temp_dir("converge_curves");
    const bool plot = gnuplot_installed();
    const test::ProgramRun run = test::run_vkrt(
        "converge " + kScene + " --width 16 --height 12 --backend vulkan --backend cpu --validate --spp 4 "
            "--reference-spp 8 -q --csv " + q(dir / "c.csv") + (plot ? " --plot " + q(dir / "c.png") : ""),
        dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("no --reference given: rendering one on vulkan"), std::string::npos)
        << run.stderr_text;

    const auto curves = by_curve(read_csv(dir / "c.csv"));
    ASSERT_EQ(curves.size(), 2u);
    for (const char* name : {"vulkan/local", "cpu/local"}) {
        SCOPED_TRACE(name);
        ASSERT_EQ(curves.count(name), 1u);
        const std::vector<CsvRow>& rows = curves.at(name);
        ASSERT_EQ(rows.size(), 3u);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            EXPECT_EQ(rows[i].spp, 1u << i);
            EXPECT_GT(rows[i].seconds, 0.0);
            if (i > 0) {
                EXPECT_GT(rows[i].seconds, rows[i - 1].seconds);
            }
            // Jittered samples against a reference of other samples: never exactly equal.
            EXPECT_GT(rows[i].rmse, 0.0);
            EXPECT_TRUE(std::isfinite(rows[i].rmse) && std::isfinite(rows[i].relmse));
            EXPECT_GT(rows[i].relmse, 0.0);
            EXPECT_GT(rows[i].mean, 0.0);
            EXPECT_TRUE(std::isfinite(rows[i].mean_diff));
            EXPECT_LT(std::abs(rows[i].mean_diff), rows[i].mean);
        }
    }
    const PartialFile reference = read_partial(dir / "c_reference.exr");
    EXPECT_EQ(format_sample_ranges(reference.samples), "0:8");
    EXPECT_EQ(reference.backend, "vulkan");
    EXPECT_EQ(reference.sums.width, 16u);
    if (plot) {
        ASSERT_TRUE(fs::exists(dir / "c.png"));
        const Image png = read_image(dir / "c.png");
        EXPECT_GT(png.width, 100u);
    } else {
        GTEST_LOG_(INFO) << "gnuplot is not installed: the plot is not checked (./scripts/setup installs it)";
    }
}

// The figures of a row are those of the image of its samples: the cpu curve's
// 4-spp row against `vkrt render --spp 4` compared with the same reference here.
TEST(Converge, ErrorFiguresAreThoseOfTheRenderedImage) {
    const fs::path dir = test::temp_dir("converge_metrics");
    const std::string size = " --width 16 --height 12 --backend cpu -q ";
    ASSERT_EQ(test::run_vkrt("render " + kScene + size + "--seed 99 --samples 0:16 -o " + q(dir / "ref.exr"), dir).code, 0);
    ASSERT_EQ(test::run_vkrt("render " + kScene + size + "--spp 4 -o " + q(dir / "four.exr"), dir).code, 0);
    const test::ProgramRun run = test::run_vkrt(
        "converge " + kScene + size + "--spp 4 --reference " + q(dir / "ref.exr") + " --csv " + q(dir / "c.csv"), dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_FALSE(fs::exists(dir / "c_reference.exr")) << "a reference was given: none is rendered";

    const std::vector<CsvRow> rows = read_csv(dir / "c.csv");
    ASSERT_EQ(rows.size(), 3u);
    const CsvRow& last = rows.back();
    ASSERT_EQ(last.spp, 4u);
    const ErrorMetrics expected = error_metrics(read_image(dir / "four.exr"), read_image(dir / "ref.exr"));
    EXPECT_NEAR(last.rmse, expected.rmse, 1e-8 * expected.rmse);
    EXPECT_NEAR(last.relmse, expected.relmse, 1e-8 * expected.relmse);
    EXPECT_NEAR(last.mean, expected.mean, 1e-8 * expected.mean);
    EXPECT_NEAR(last.mean_diff, expected.mean_diff, 1e-7 * expected.mean);
}

// Estimators multiply the curves; on a local-mode scene they change nothing, and
// a warning says so.
TEST(Converge, OneCurvePerEstimator) {
    const fs::path dir = test::temp_dir("converge_estimators");
    const test::ProgramRun run = test::run_vkrt(
        "converge " + kScene + " --width 8 --height 6 --backend cpu --estimator path:uniform --estimator path+nee "
            "--estimator paper --spp 2 --reference-spp 4 -q --csv " + q(dir / "c.csv"),
        dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("warning:"), std::string::npos);
    EXPECT_NE(run.stderr_text.find("local mode"), std::string::npos) << run.stderr_text;
    const auto curves = by_curve(read_csv(dir / "c.csv"));
    ASSERT_EQ(curves.size(), 3u);
    for (const char* name : {"cpu/path:uniform@sobol", "cpu/path+nee:cosine@sobol", "cpu/paper:angles@sobol"}) {
        ASSERT_EQ(curves.count(name), 1u) << name;
        EXPECT_EQ(curves.at(name).size(), 2u) << name;
    }
}

// In global mode each spec renders with its own estimator: the curves differ, and
// without --estimator the label is the scene's own settings in full.
TEST(Converge, EstimatorsReachTheGlobalModeKernel) {
    const fs::path dir = test::temp_dir("converge_global");
    const std::string room = q(test::source_dir() / "scenes" / "gallery" / "k_room.json");
    const std::string base = "converge " + room + " --width 16 --height 12 --backend cpu --spp 2 -q --reference-spp 4 ";
    const test::ProgramRun run = test::run_vkrt(
        base + "--estimator path:uniform@hash --estimator path:cosine --estimator paper --csv " + q(dir / "c.csv"), dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_EQ(run.stderr_text.find("local mode"), std::string::npos) << run.stderr_text;
    const auto curves = by_curve(read_csv(dir / "c.csv"));
    ASSERT_EQ(curves.size(), 3u);
    const double uniform = curves.at("cpu/path:uniform@hash").front().rmse;
    const double cosine = curves.at("cpu/path:cosine@sobol").front().rmse;
    const double paper = curves.at("cpu/paper:angles@sobol").front().rmse;
    EXPECT_NE(uniform, cosine);
    EXPECT_NE(uniform, paper);
    EXPECT_NE(cosine, paper);

    const test::ProgramRun own = test::run_vkrt(base + "--csv " + q(dir / "own.csv"), dir);
    ASSERT_EQ(own.code, 0) << own.stderr_text;
    const auto own_curves = by_curve(read_csv(dir / "own.csv"));
    ASSERT_EQ(own_curves.size(), 1u);
    EXPECT_EQ(own_curves.begin()->first, "cpu/path+nee:cosine@sobol");
}

// --until: the curve ends when its time is spent, at checkpoints of 1, 2, 4, ...
// and a last row where it stopped. How far a curve gets in its time depends on the
// machine; the checks hold on any: a budget spent by the first pass ends the curve
// at its first checkpoint, and a longer one (with no sample limit) gives rows at
// the checkpoints, then at most one more, short of the next checkpoint.
TEST(Converge, UntilStopsEachCurveByTime) {
    const fs::path dir = test::temp_dir("converge_until");
    auto curve_for = [&](const std::string& seconds, const std::string& name) {
        const test::ProgramRun run = test::run_vkrt("converge " + kScene +
                                                        " --width 16 --height 12 --backend cpu --threads 1 --until " +
                                                        seconds + " --reference-spp 4 -q --csv " + q(dir / name),
                                                    dir);
        EXPECT_EQ(run.code, 0) << run.stderr_text;
        return read_csv(dir / name);
    };

    const std::vector<CsvRow> spent = curve_for("1e-12", "spent.csv");
    ASSERT_EQ(spent.size(), 1u);
    EXPECT_EQ(spent[0].spp, 1u);

    const std::vector<CsvRow> rows = curve_for("0.3", "c.csv");
    ASSERT_GE(rows.size(), 1u);
    ASSERT_LT(rows.size(), 32u);
    for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
        EXPECT_EQ(rows[i].spp, 1u << i);
        EXPECT_LT(rows[i].seconds, rows[i + 1].seconds);
    }
    const std::uint32_t last = rows.back().spp;
    if (rows.size() > 1) {
        const std::uint32_t before = rows[rows.size() - 2].spp;
        EXPECT_GT(last, before);
        EXPECT_LE(last, 2 * before) << "a checkpoint was passed without a row";
    }
    EXPECT_LT(last, limits::kMaxSpp) << "the sample limit, not the time, ended the curve";
    EXPECT_TRUE(rows.back().seconds > 0.0 && std::isfinite(rows.back().seconds)) << rows.back().seconds;
}

TEST(Converge, MistakesAreOneClearError) {
    const fs::path dir = test::temp_dir("converge_errors");
    ASSERT_EQ(test::run_vkrt("render " + kScene + " --width 8 --height 6 --backend cpu -q -o " + q(dir / "small.exr"), dir).code, 0);
    ASSERT_EQ(test::run_vkrt("render " + kScene + " --width 8 --height 6 --backend cpu -q -o " + q(dir / "small.png"), dir).code, 0);
    const std::string base = "converge " + kScene + " --width 16 --height 12 --backend cpu --spp 2 --csv " + q(dir / "c.csv");

    test::expect_one_error(test::run_vkrt(base + " --estimator path:sphere", dir), {"--estimator", "path:sphere", "angles, uniform or cosine"});
    test::expect_one_error(test::run_vkrt(base + " --estimator bidir", dir), {"--estimator", "'bidir'", "paper, path or path+nee"});
    test::expect_one_error(test::run_vkrt(base + " --estimator paper+nee", dir), {"--estimator", "no next-event estimation"});
    test::expect_one_error(test::run_vkrt(base + " --estimator path+nee@halton", dir),
                           {"--estimator", "unknown sampler 'halton'", "sobol or hash"});
    test::expect_one_error(test::run_vkrt(base + " --estimator path@sobol --estimator path", dir), {"given twice"});
    test::expect_one_error(test::run_vkrt(base + " --estimator path --estimator path:cosine", dir), {"--estimator", "given twice"});
    test::expect_one_error(test::run_vkrt(base + " --backend cpu", dir), {"--backend cpu", "given twice"});
    test::expect_one_error(test::run_vkrt(base + " --backend metal", dir), {"--backend", "metal"});
    test::expect_one_error(test::run_vkrt(base + " --reference " + q(dir / "missing.exr"), dir), {"missing.exr", "no such file"});
    test::expect_one_error(test::run_vkrt(base + " --reference " + q(dir / "small.exr"), dir), {"small.exr", "8x6", "16x12"});
    test::expect_one_error(test::run_vkrt(base + " --reference " + q(dir / "small.png"), dir), {"small.png", ".exr or .hdr"});
    test::expect_one_error(test::run_vkrt(base + " --until 0", dir), {"--until", "'0'"});
    test::expect_one_error(test::run_vkrt(base + " --plot " + q(dir / "c.jpg"), dir), {"c.jpg", ".png"});
    test::expect_one_error(test::run_vkrt("converge " + kScene + " --csv /nonexistent/dir/c.csv", dir), {"no directory /nonexistent/dir"});
    test::expect_one_error(test::run_vkrt("converge " + kScene, dir), {"--csv", "required"});

    // Without gnuplot, --plot fails before rendering and names the package to install.
    ASSERT_EQ(setenv("VKRT_GNUPLOT", "/nonexistent/gnuplot", 1), 0);
    const test::ProgramRun no_gnuplot = test::run_vkrt(base + " --plot " + q(dir / "c.png"), dir);
    unsetenv("VKRT_GNUPLOT");
    test::expect_one_error(no_gnuplot, {"--plot", "gnuplot-nox"});
    EXPECT_FALSE(fs::exists(dir / "c.csv")) << "nothing is written after an error";
    EXPECT_FALSE(fs::exists(dir / "c_reference.exr"));
}

}  // namespace
