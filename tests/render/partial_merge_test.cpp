// Split rendering through the real program: `vkrt render --samples A:B` writes
// partial files and `vkrt merge` adds them up into the image of one run, bit for
// bit; and every mistake a user can make with them is one clear error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/partial_file.hpp"
#include "render/sample_ranges.hpp"
#include "scene/limits.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

std::string q(const fs::path& p) { return test::shell_quote(p.string()); }

// Jittered antialiasing: every sample index traces different rays.
const fs::path& jittered_scene() {
    static const fs::path scene = test::source_dir() / "scenes" / "spheres_triangles.json";
    return scene;
}

class PartialMerge : public ::testing::Test {
public:
    void SetUp() override {
        dir_ = test::temp_dir(std::string("partial_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    // Renders the jittered scene at 32x24 with extra arguments; fails the test on error.
    void render(const std::string& backend, const std::string& args) {
        const test::ProgramRun run = test::run_vkrt("render " + q(jittered_scene()) + " --width 32 --height 24 -q --backend " +
                                                        backend + (backend == "vulkan" ? " --validate " : " ") + args,
                                                    dir_);
        ASSERT_EQ(run.code, 0) << args << "\n" << run.stderr_text;
    }
    test::ProgramRun merge(const std::string& args) { return test::run_vkrt("merge " + args, dir_); }
    fs::path at(const std::string& name) const { return dir_ / name; }

    fs::path dir_;  // public: the free helper below drives the fixture too
};

std::string read_file(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Samples 0:2 and 2:5 merged, in either order, against one render of 5 samples:
// the float pixels of the EXR files are equal exactly, and so are the sums and
// counters the partial files carry.
void expect_split_equals_whole(PartialMerge& t, const std::string& backend) {
    t.render(backend, "--samples 0:2 -o " + q(t.at("a.exr")));
    t.render(backend, "--samples 2:5 -o " + q(t.at("b.exr")));
    t.render(backend, "--spp 5 -o " + q(t.at("whole.exr")));
    t.render(backend, "--samples 0:5 -o " + q(t.at("whole_partial.exr")));
    ASSERT_EQ(t.merge(q(t.at("a.exr")) + " " + q(t.at("b.exr")) + " -q -o " + q(t.at("ab.exr"))).code, 0);
    ASSERT_EQ(t.merge(q(t.at("b.exr")) + " " + q(t.at("a.exr")) + " -q -o " + q(t.at("ba.exr"))).code, 0);

    const Image whole = read_image(t.at("whole.exr"));
    for (const char* merged : {"ab.exr", "ba.exr"}) {
        SCOPED_TRACE(merged);
        const Image image = read_image(t.at(merged));
        ASSERT_EQ(image.width, 32u);
        ASSERT_EQ(image.height, 24u);
        EXPECT_EQ(image.rgb, whole.rgb);
        const PartialFile partial = read_partial(t.at(merged));
        const PartialFile reference = read_partial(t.at("whole_partial.exr"));
        EXPECT_EQ(partial.sums.sums, reference.sums.sums);
        EXPECT_EQ(partial.sums.counters, reference.sums.counters);
        ASSERT_EQ(partial.samples.size(), 1u);
        EXPECT_EQ(partial.samples[0].first, 0u);
        EXPECT_EQ(partial.samples[0].count, 5u);
        EXPECT_EQ(partial.backend, backend);
    }
    // The two halves really differ: the merge added different samples.
    const Image a = read_image(t.at("a.exr")), b = read_image(t.at("b.exr"));
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) differing += std::abs(a.rgb[i] - b.rgb[i]) > 1e-4f ? 1 : 0;
    EXPECT_GT(differing, 30u);
}

TEST_F(PartialMerge, ReferenceBackendMergesBitForBit) { expect_split_equals_whole(*this, "cpu"); }

// On Vulkan too the exact sums make the merged image the whole render's bit for
// bit, not merely close to it, and that is what is asserted.
TEST_F(PartialMerge, VulkanBackendMergesBitForBit) { expect_split_equals_whole(*this, "vulkan"); }

// Three partials merged in any grouping and order give the same file contents, and
// a merge's .exr output is itself a partial that merges again (an intermediate one
// may leave a gap, when allowed).
TEST_F(PartialMerge, OrderAndGroupingDoNotMatter) {
    render("cpu", "--samples 0:1 -o " + q(at("p0.exr")));
    render("cpu", "--samples 1:3 -o " + q(at("p1.exr")));
    render("cpu", "--samples 3:6 -o " + q(at("p2.exr")));
    ASSERT_EQ(merge(q(at("p0.exr")) + " " + q(at("p1.exr")) + " " + q(at("p2.exr")) + " -q -o " + q(at("flat.exr"))).code, 0);
    ASSERT_EQ(merge(q(at("p2.exr")) + " " + q(at("p0.exr")) + " --allow-gaps -q -o " + q(at("p20.exr"))).code, 0);
    ASSERT_EQ(merge(q(at("p1.exr")) + " " + q(at("p20.exr")) + " -q -o " + q(at("nested.exr"))).code, 0);
    const PartialFile flat = read_partial(at("flat.exr"));
    const PartialFile nested = read_partial(at("nested.exr"));
    EXPECT_EQ(flat.sums.sums, nested.sums.sums);
    EXPECT_EQ(flat.sums.counters, nested.sums.counters);
    EXPECT_EQ(format_sample_ranges(nested.samples), "0:6");
    EXPECT_EQ(read_image(at("flat.exr")).rgb, read_image(at("nested.exr")).rgb);
    // And to an 8-bit image, as render writes one.
    ASSERT_EQ(merge(q(at("nested.exr")) + " -q -o " + q(at("nested.png"))).code, 0);
    render("cpu", "--spp 6 -o " + q(at("whole.png")));
    EXPECT_EQ(read_image(at("nested.png")).rgb, read_image(at("whole.png")).rgb);
}

// The attributes say what was rendered; without -o the name says the range.
TEST_F(PartialMerge, PartialFileRecordsItsRenderAndHasADefaultName) {
    const fs::path previous = fs::current_path();
    fs::current_path(dir_);
    render("cpu", "--samples 4:7 --seed 11");
    fs::current_path(previous);
    ASSERT_TRUE(fs::exists(at("spheres_triangles_4-7.exr")));
    const PartialFile p = read_partial(at("spheres_triangles_4-7.exr"));
    EXPECT_EQ(format_sample_ranges(p.samples), "4:7");
    EXPECT_EQ(p.scene, "spheres_triangles.json");
    EXPECT_EQ(p.seed, 11u);
    EXPECT_EQ(p.backend, "cpu");
    EXPECT_FALSE(p.corners);
    EXPECT_NE(p.fingerprint, 0u);
    ASSERT_EQ(p.sums.sums.size(), 32u * 24u);
    for (const kernel::PixelSum& s : p.sums.sums) ASSERT_EQ(s.red.w, 3u);  // every pixel has the 3 samples
}

// A merge that leaves a hole is refused, naming it; --allow-gaps merges anyway and
// says so.
TEST_F(PartialMerge, GapsAreNamedAndRefusedUnlessAllowed) {
    render("cpu", "--samples 0:2 -o " + q(at("a.exr")));
    render("cpu", "--samples 5:6 -o " + q(at("c.exr")));
    const std::string both = q(at("a.exr")) + " " + q(at("c.exr"));
    test::expect_one_error(merge(both + " -o " + q(at("gap.exr"))), {"samples 2:5 are missing", "--missing", "--allow-gaps"});
    EXPECT_FALSE(fs::exists(at("gap.exr")));
    // The samples wanted name what is missing at the ends too: a lost last task.
    test::expect_one_error(merge(both + " --samples 0:8 -o " + q(at("gap.exr"))), {"samples 2:5,6:8 are missing"});
    test::expect_one_error(merge(both + " --samples 0:4 -o " + q(at("gap.exr"))), {"c.exr holds samples 5:6", "outside --samples 0:4"});
    const test::ProgramRun run = merge(both + " --allow-gaps -o " + q(at("gap.exr")));
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("warning: the partials leave out samples 2:5"), std::string::npos) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("average of the 3 samples"), std::string::npos) << run.stderr_text;
    const std::string log = read_file(at("stdout.txt"));
    EXPECT_NE(log.find("samples 0:2,5:6: 3 per pixel"), std::string::npos) << log;
    EXPECT_EQ(format_sample_ranges(read_partial(at("gap.exr")).samples), "0:2,5:6");
}

// --missing lists what is left to render, one range a line, cut for --tasks
// machines; a damaged partial counts as missing.
TEST_F(PartialMerge, MissingListsTheRangesLeftToRender) {
    render("cpu", "--samples 0:2 -o " + q(at("a.exr")));
    render("cpu", "--samples 5:6 -o " + q(at("c.exr")));
    const std::string both = q(at("a.exr")) + " " + q(at("c.exr"));
    auto listed = [&](const std::string& args) {
        const test::ProgramRun run = merge("--missing " + args);
        EXPECT_EQ(run.code, 0) << run.stderr_text;
        return read_file(at("stdout.txt"));
    };
    EXPECT_EQ(listed("--samples 0:10 " + both), "2:5\n6:10\n");
    EXPECT_EQ(listed("--samples 0:10 --tasks 7 " + both), "2:3\n3:4\n4:5\n6:7\n7:8\n8:9\n9:10\n");
    EXPECT_EQ(listed("--samples 0:6 " + both), "2:5\n");
    EXPECT_EQ(listed("--samples 0:100 --tasks 4"), "0:25\n25:50\n50:75\n75:100\n");
    test::expect_one_error(merge("--missing " + both), {"--missing needs --samples"});
    test::expect_one_error(merge("--missing --samples 5:2 " + both), {"--samples", "'5:2'", "empty range"});
    test::expect_one_error(merge("--missing --samples 0:6 --tasks 0 " + both), {"--tasks"});
    test::expect_one_error(merge("--samples 0:6 --tasks 2 " + both + " -o " + q(at("x.exr"))), {"--tasks", "--missing"});
    test::expect_one_error(merge("--samples 0:6"), {"--output is required"});
    test::expect_one_error(merge("--samples 0:6 -o " + q(at("x.exr"))), {"no partial files given"});
    test::expect_one_error(merge("--missing --samples 0:6 " + both + " -o " + q(at("x.exr"))), {"--missing", "--output"});
    // Cut short, as by a task killed while writing.
    fs::copy_file(at("c.exr"), at("cut.exr"));
    fs::resize_file(at("cut.exr"), fs::file_size(at("cut.exr")) / 2);
    const test::ProgramRun run = merge("--missing --samples 0:6 " + q(at("a.exr")) + " " + q(at("cut.exr")));
    EXPECT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_EQ(read_file(at("stdout.txt")), "2:6\n");
    EXPECT_NE(run.stderr_text.find("cut.exr"), std::string::npos) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("count as missing"), std::string::npos) << run.stderr_text;
}

// A truncated or damaged partial is refused with what to do, never merged.
TEST_F(PartialMerge, DamagedPartialsAreRefused) {
    render("cpu", "--samples 0:2 -o " + q(at("a.exr")));
    render("cpu", "--samples 2:4 -o " + q(at("b.exr")));
    fs::copy_file(at("b.exr"), at("cut.exr"));
    fs::resize_file(at("cut.exr"), fs::file_size(at("cut.exr")) * 3 / 4);
    test::expect_one_error(merge(q(at("a.exr")) + " " + q(at("cut.exr")) + " -o " + q(at("out.exr"))),
                           {"cut.exr", "truncated or damaged", "render its samples (2:4) again"});
    // Bytes changed inside the pixel data, the file's size and header intact.
    fs::copy_file(at("b.exr"), at("flipped.exr"));
    {
        std::fstream f(at("flipped.exr"), std::ios::in | std::ios::out | std::ios::binary);
        const auto size = std::streamoff(fs::file_size(at("flipped.exr")));
        for (const std::streamoff at : {size * 6 / 10, size * 7 / 10, size * 8 / 10}) {
            f.seekg(at);
            const char c = char(f.get() ^ 0x5a);
            f.seekp(at);
            f.put(c);
        }
    }
    test::expect_one_error(merge(q(at("a.exr")) + " " + q(at("flipped.exr")) + " -o " + q(at("out.exr"))),
                           {"flipped.exr", "damaged", "render its samples (2:4) again"});
    EXPECT_FALSE(fs::exists(at("out.exr")));
}

// Partials from builds whose kernels differ are refused, naming both versions.
TEST_F(PartialMerge, PartialsOfAnotherBuildAreRefused) {
    render("cpu", "--samples 0:2 -o " + q(at("a.exr")));
    render("cpu", "--samples 2:4 -o " + q(at("b.exr")));
    PartialFile b = read_partial(at("b.exr"));
    EXPECT_EQ(b.version, build_version());
    b.version = "0.0.1 kernel 000000000000";
    write_partial(b, at("old.exr"));
    test::expect_one_error(merge(q(at("a.exr")) + " " + q(at("old.exr")) + " -o " + q(at("out.exr"))),
                           {"old.exr was rendered by vkrt 0.0.1 kernel 000000000000", build_version(), "render one of them again"});
}

TEST_F(PartialMerge, BadSampleRangesAreRefused) {
    const std::string base = "render " + q(jittered_scene()) + " --backend cpu --width 32 --height 24 -o " + q(at("x.exr"));
    test::expect_one_error(test::run_vkrt(base + " --samples 5:2", dir_), {"--samples", "'5:2'", "empty range", "below the end"});
    test::expect_one_error(test::run_vkrt(base + " --samples 3:3", dir_), {"--samples", "'3:3'", "empty range"});
    test::expect_one_error(test::run_vkrt(base + " --samples 0:65537", dir_), {"--samples", "'0:65537'", "65536"});
    for (const char* malformed : {"7", "a:b", "1:", ":4", "-1:3", "1:2:3", "1.5:3"}) {
        test::expect_one_error(test::run_vkrt(base + " --samples " + test::shell_quote(malformed), dir_),
                     {"--samples", "expected A:B", malformed});
    }
    test::expect_one_error(test::run_vkrt(base + " --samples 0:2 --spp 2", dir_), {"--samples", "--spp"});
    test::expect_one_error(test::run_vkrt(base + " --samples 0:2 --time 1", dir_), {"--samples", "--time"});
    test::expect_one_error(test::run_vkrt("render " + q(jittered_scene()) + " --backend cpu --samples 0:2 -o " + q(at("x.png")), dir_),
                 {"x.png", "--samples writes a partial file", ".exr"});
    EXPECT_FALSE(fs::exists(at("x.exr")));
    EXPECT_FALSE(fs::exists(at("x.png")));
}

TEST_F(PartialMerge, MismatchedPartialsAreRefused) {
    render("cpu", "--samples 0:3 -o " + q(at("a.exr")));
    render("cpu", "--samples 2:5 -o " + q(at("overlapping.exr")));
    render("cpu", "--samples 3:5 --seed 8 -o " + q(at("other_seed.exr")));
    render("cpu", "--spp 2 -o " + q(at("plain.exr")));
    const test::ProgramRun other_scene = test::run_vkrt(
        "render " + q(test::source_dir() / "scenes" / "default.json") +
            " --backend cpu --width 32 --height 24 -q --samples 3:5 -o " + q(at("other_scene.exr")),
        dir_);
    ASSERT_EQ(other_scene.code, 0) << other_scene.stderr_text;
    const test::ProgramRun other_size = test::run_vkrt(
        "render " + q(jittered_scene()) + " --backend cpu --width 16 --height 24 -q --samples 3:5 -o " +
            q(at("other_size.exr")),
        dir_);
    ASSERT_EQ(other_size.code, 0) << other_size.stderr_text;
    const std::string a = q(at("a.exr")), out = " -o " + q(at("out.exr"));

    test::expect_one_error(merge(a + " " + q(at("overlapping.exr")) + out), {"a.exr (samples 0:3)", "overlapping.exr (samples 2:5)",
                                                                  "overlap in samples 2:3"});
    test::expect_one_error(merge(a + " " + a + out), {"a.exr", "given twice"});
    test::expect_one_error(merge(a + " " + q(at("other_seed.exr")) + out), {"other_seed.exr", "seed 8", "seed 7", "not a render of the same scene"});
    test::expect_one_error(merge(a + " " + q(at("other_scene.exr")) + out), {"other_scene.exr", "'default.json'", "'spheres_triangles.json'"});
    test::expect_one_error(merge(a + " " + q(at("other_size.exr")) + out), {"other_size.exr is 16x24", "a.exr is 32x24"});
    test::expect_one_error(merge(a + " " + q(at("plain.exr")) + out), {"plain.exr", "not a vkrt partial file"});
    std::ofstream(at("text.exr")) << "not an image";
    test::expect_one_error(merge(a + " " + q(at("text.exr")) + out), {"text.exr"});
    test::expect_one_error(merge(a + " " + q(at("missing.exr")) + out), {"missing.exr", "no such file"});
    test::expect_one_error(merge(a + " -o " + q(at("out.xyz"))), {"out.xyz", "unknown image format"});
    test::expect_one_error(merge(a), {"--output", "required"});
    EXPECT_FALSE(fs::exists(at("out.exr")));
}

TEST(SampleRanges, ParseAndPrint) {
    const SampleRange r = parse_sample_range("2:5", limits::kMaxSpp);
    EXPECT_EQ(r.first, 2u);
    EXPECT_EQ(r.count, 3u);
    EXPECT_EQ(format_sample_range(r), "2:5");
    EXPECT_NO_THROW(parse_sample_range("0:65536", limits::kMaxSpp));
    EXPECT_THROW(parse_sample_range("0:65537", limits::kMaxSpp), std::invalid_argument);
    EXPECT_THROW(parse_sample_range("99999999999:1", limits::kMaxSpp), std::invalid_argument);
    const auto list = parse_sample_ranges("5:8,0:2", limits::kMaxSpp);
    ASSERT_TRUE(list);
    EXPECT_EQ(format_sample_ranges(normalize_sample_ranges(*list)), "0:2,5:8");
    EXPECT_FALSE(parse_sample_ranges("", limits::kMaxSpp));
    EXPECT_FALSE(parse_sample_ranges("0:2,", limits::kMaxSpp));
    EXPECT_FALSE(parse_sample_ranges("2:1", limits::kMaxSpp));
}

TEST(SampleRanges, JoinOverlapAndGaps) {
    EXPECT_EQ(format_sample_ranges(normalize_sample_ranges({{2, 3}, {0, 2}, {5, 1}})), "0:6");
    const auto both = overlap({0, 3}, {2, 3});
    ASSERT_TRUE(both);
    EXPECT_EQ(format_sample_range(*both), "2:3");
    EXPECT_FALSE(overlap({0, 2}, {2, 3}));
    EXPECT_EQ(format_sample_ranges(sample_gaps({{6, 2}, {0, 2}, {3, 1}})), "2:3,4:6");
    EXPECT_TRUE(sample_gaps({{1, 2}, {3, 1}}).empty());
    EXPECT_EQ(sample_count({{0, 2}, {5, 3}}), 5u);
}

TEST(SampleRanges, MissingAndSplit) {
    EXPECT_EQ(format_sample_ranges(missing_samples({0, 10}, {{6, 2}, {0, 2}})), "2:6,8:10");
    EXPECT_EQ(format_sample_ranges(missing_samples({4, 4}, {{0, 5}, {7, 9}})), "5:7");
    EXPECT_TRUE(missing_samples({0, 3}, {{0, 3}}).empty());
    EXPECT_EQ(format_sample_ranges(missing_samples({0, 3}, {})), "0:3");
    // 10 samples on 3 machines: 3, 3 and 4; a range is never cut finer than samples.
    EXPECT_EQ(format_sample_ranges(split_sample_ranges({{0, 10}}, 3)), "0:3,3:6,6:10");
    EXPECT_EQ(format_sample_ranges(split_sample_ranges({{0, 2}}, 5)), "0:1,1:2");
    // Pieces by share: 90 samples get 9 of 10 machines, a gap of 10 the last.
    EXPECT_EQ(split_sample_ranges({{0, 90}, {100, 10}}, 10).size(), 10u);
    EXPECT_EQ(format_sample_ranges(split_sample_ranges({{0, 4}, {9, 1}}, 0)), "0:4,9:10");
}

}  // namespace
