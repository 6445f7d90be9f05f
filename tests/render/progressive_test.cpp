// Progressive rendering: the pass-size rule, passes that add up to one render
// exactly, and the --time budget through the real program.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu/vulkan_backend.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/pass_plan.hpp"
#include "render/pixel_sums.hpp"
#include "render/progressive.hpp"
#include "render/render.hpp"
#include "scene/limits.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

// The passes a render of `limit` samples takes when each sample costs `seconds`.
std::vector<std::uint32_t> passes(std::uint32_t limit, double seconds, std::optional<double> budget = {}) {
    std::vector<std::uint32_t> out;
    std::uint32_t done = 0;
    double spent = 0.0;
    for (;;) {
        PassPlanInput in{done, limit - done, done == 0 ? 0.0 : seconds, {}};
        if (budget) in.seconds_left = *budget - spent;
        const std::uint32_t n = next_pass_samples(in);
        if (n == 0) return out;
        out.push_back(n);
        done += n;
        spent += n * seconds;
    }
}

TEST(PassPlan, DoublesSoThatTheCountsDoneArePowersOfTwo) {
    EXPECT_EQ(passes(16, 0.001), (std::vector<std::uint32_t>{1, 1, 2, 4, 8}));
    // The sample limit cuts the last pass.
    EXPECT_EQ(passes(11, 0.001), (std::vector<std::uint32_t>{1, 1, 2, 4, 3}));
    EXPECT_EQ(passes(1, 0.001), (std::vector<std::uint32_t>{1}));
}

TEST(PassPlan, APassStaysAroundASecond) {
    // 0.3 s a sample: at most 3 samples (0.9 s) a pass once doubling would pass that.
    EXPECT_EQ(passes(20, 0.3), (std::vector<std::uint32_t>{1, 1, 2, 3, 3, 3, 3, 3, 1}));
    // A sample slower than the pass target still renders, one a pass.
    EXPECT_EQ(passes(3, 2.5), (std::vector<std::uint32_t>{1, 1, 1}));
}

TEST(PassPlan, ATimeBudgetIsMetToHalfASample) {
    // 0.1 s a sample, 1 s budget: 10 samples exactly.
    std::uint32_t total = 0;
    for (std::uint32_t n : passes(1000, 0.1, 1.0)) total += n;
    EXPECT_EQ(total, 10u);
    // 0.38 s a sample, 1 s budget: 1 + 1 (0.76 s), then 0.24 s left is 0.63 of a
    // sample, rounded to the nearest: one more (1.14 s, 0.14 over) rather than
    // stopping 0.24 under. At 0.45 s a sample the 0.1 s left round to none.
    EXPECT_EQ(passes(1000, 0.38, 1.0), (std::vector<std::uint32_t>{1, 1, 1}));
    EXPECT_EQ(passes(1000, 0.45, 1.0), (std::vector<std::uint32_t>{1, 1}));
    // The first pass renders even when the budget is already spent: an image needs a sample.
    EXPECT_EQ(passes(1000, 5.0, 0.001), (std::vector<std::uint32_t>{1}));
}

// The samples of each pass, rendering until `render` stops at `stop_at`.
std::vector<std::uint32_t> pass_sizes(ProgressiveRender& render,
                                      std::uint32_t stop_at = std::numeric_limits<std::uint32_t>::max(),
                                      const ProgressiveCallback& progress = {}) {
    std::vector<std::uint32_t> sizes;
    for (std::uint32_t before = render.samples_done(); render.next_pass(stop_at, progress);
         before = render.samples_done()) {
        sizes.push_back(render.samples_done() - before);
    }
    return sizes;
}

// The pass-size rule whatever the clock said (PassPlan above pins the sizes for
// given sample costs): one sample first, then never more than are done already.
// With fast samples the passes are 1, 1, 2, 4, ...; slow ones only make them smaller.
void expect_doubling_at_most(const std::vector<std::uint32_t>& sizes) {
    ASSERT_FALSE(sizes.empty());
    EXPECT_EQ(sizes.front(), 1u);
    std::uint32_t done = 0;
    for (const std::uint32_t n : sizes) {
        EXPECT_GE(n, 1u);
        if (done > 0) {
            EXPECT_LE(n, done) << "after " << done << " samples";
        }
        done += n;
    }
}

// Passes through one session add up, bit for bit, to one render of all the samples,
// and a later first sample renders the later indices (split rendering).
void expect_passes_equal_one_render(Backend& backend) {
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "spheres_triangles.json", 32, 24);
    const FlatScene gpu = flatten_scene(scene, backend.accel_policy());
    const RenderResult whole = backend.render(gpu, SampleRange{3, 9});
    const std::unique_ptr<RenderSession> session = backend.begin(gpu);
    ProgressiveRender render(*session, {SampleRange{3, 9}, std::nullopt});
    std::vector<double> reported;
    const std::vector<std::uint32_t> sizes =
        pass_sizes(render, std::numeric_limits<std::uint32_t>::max(),
                   [&](const ProgressiveStatus& s) { reported.push_back(s.samples); });
    expect_doubling_at_most(sizes);
    EXPECT_EQ(render.samples_done(), 9u);
    EXPECT_EQ(render.passes(), sizes.size());
    EXPECT_FALSE(render.stopped_by_time());
    EXPECT_EQ(render.total().sums, whole.sums);
    EXPECT_EQ(render.total().counters, whole.counters);
    ASSERT_FALSE(reported.empty());
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
    EXPECT_DOUBLE_EQ(reported.back(), 9.0);
}

TEST(Progressive, ReferencePassesEqualOneRender) {
    auto backend = make_cpu_backend();
    expect_passes_equal_one_render(*backend);
}

TEST(Progressive, VulkanPassesEqualOneRender) {
    auto backend = make_vulkan_backend(VulkanOptions{"", true});
    expect_passes_equal_one_render(*backend);
    EXPECT_EQ(backend->validation_messages(), 0u);
}

// Checkpoints cut passes: with stop_at, a pass never runs past it.
TEST(Progressive, PassesStopAtCheckpoints) {
    auto backend = make_cpu_backend();
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "spheres_triangles.json", 8, 6);
    const FlatScene gpu = flatten_scene(scene);
    const std::unique_ptr<RenderSession> session = backend->begin(gpu);
    ProgressiveRender render(*session, {SampleRange{0, 7}, std::nullopt});
    std::vector<std::uint32_t> done;
    for (std::uint32_t checkpoint : {1u, 3u, 7u}) {
        while (render.next_pass(checkpoint)) {
        }
        done.push_back(render.samples_done());
    }
    EXPECT_EQ(done, (std::vector<std::uint32_t>{1, 3, 7}));
    EXPECT_FALSE(render.next_pass());
}

// A budget that is spent before the first pass ends: that pass still renders its
// one sample (an image needs one), and none follows. A picosecond is shorter than
// any pass, so no machine, however busy, can make this come out otherwise.
TEST(Progressive, ASpentBudgetStillRendersTheFirstSample) {
    auto backend = make_cpu_backend(1);
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "spheres_triangles.json", 8, 6);
    const FlatScene gpu = flatten_scene(scene);
    const std::unique_ptr<RenderSession> session = backend->begin(gpu);
    ProgressiveRender render(*session, {SampleRange{0, 100}, 1e-12});
    EXPECT_EQ(pass_sizes(render), (std::vector<std::uint32_t>{1}));
    EXPECT_TRUE(render.stopped_by_time());
    EXPECT_EQ(render.samples_done(), 1u);
    EXPECT_FALSE(render.next_pass()) << "a stopped render stays stopped";
}

// A budget no render here comes near: the sample limit ends the render, and the
// render says so.
TEST(Progressive, TheSampleLimitEndsARenderWithinItsBudget) {
    auto backend = make_cpu_backend(1);
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "spheres_triangles.json", 8, 6);
    const FlatScene gpu = flatten_scene(scene);
    const std::unique_ptr<RenderSession> session = backend->begin(gpu);
    ProgressiveRender render(*session, {SampleRange{0, 9}, 1e9});
    expect_doubling_at_most(pass_sizes(render));
    EXPECT_EQ(render.samples_done(), 9u);
    EXPECT_FALSE(render.stopped_by_time());
}

nlohmann::json read_json(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

// --time through the program, with no sample limit. How many samples fit in a
// budget depends on the machine, so what is checked is what holds on any: a
// budget spent by the first pass gives exactly one sample; a longer one stops the
// render by time, with every pixel at the same count and the passes following the
// pass-size rule (each at least one sample, at most the samples done before it).
TEST(Progressive, TimeBudgetStopsTheRender) {
    const fs::path dir = test::temp_dir("progressive_time");
    const std::string scene = test::shell_quote((test::source_dir() / "scenes" / "spheres_triangles.json").string());
    const std::string size = " --backend cpu --threads 1 --width 32 --height 24 -q ";
    auto render_for = [&](const std::string& seconds, const std::string& name) {
        const test::ProgramRun run =
            test::run_vkrt("render " + scene + size + "--time " + seconds + " -o " +
                               test::shell_quote((dir / (name + ".exr")).string()) + " --stats " +
                               test::shell_quote((dir / (name + ".json")).string()),
                           dir);
        EXPECT_EQ(run.code, 0) << run.stderr_text;
        return read_json(dir / (name + ".json"));
    };

    const nlohmann::json spent = render_for("1e-12", "spent");
    EXPECT_EQ(spent["samples_per_pixel"].get<std::uint32_t>(), 1u);
    EXPECT_EQ(spent["passes"].get<std::uint32_t>(), 1u);
    EXPECT_TRUE(spent["stopped_by_time"].get<bool>());
    EXPECT_EQ(spent["rays"]["eye"].get<std::uint64_t>(), std::uint64_t(32) * 24);

    const nlohmann::json stats = render_for("0.5", "budget");
    const std::uint32_t spp = stats["samples_per_pixel"];
    const std::uint32_t passes = stats["passes"];
    EXPECT_TRUE(stats["stopped_by_time"].get<bool>());
    EXPECT_LT(spp, limits::kMaxSpp);
    ASSERT_GE(passes, 1u);
    ASSERT_LT(passes, 32u);
    EXPECT_GE(spp, passes);
    EXPECT_LE(spp, 1u << (passes - 1));
    EXPECT_EQ(stats["rays"]["eye"].get<std::uint64_t>(), std::uint64_t(32) * 24 * spp);
    const double pass_seconds = stats["seconds"]["passes"].get<double>();
    EXPECT_TRUE(pass_seconds > 0.0 && std::isfinite(pass_seconds)) << pass_seconds;

    // With --spp too, whichever comes first: here the sample count.
    const test::ProgramRun both = test::run_vkrt("render " + scene + " --backend cpu --width 32 --height 24 --time 1e9 "
                                                 "--spp 3 -q -o " + test::shell_quote((dir / "u.exr").string()) +
                                                 " --stats " + test::shell_quote((dir / "u.json").string()),
                                                 dir);
    ASSERT_EQ(both.code, 0) << both.stderr_text;
    const nlohmann::json u = read_json(dir / "u.json");
    EXPECT_EQ(u["samples_per_pixel"].get<std::uint32_t>(), 3u);
    EXPECT_FALSE(u["stopped_by_time"].get<bool>());
}

}  // namespace
