// The float probe of `vkrt devices --float-profile` (docs/numerics.md): the CPU column
// is IEEE-754 binary32 as the reference backend computes it, lavapipe runs the probe
// cleanly and within the Vulkan spec's precision table, and the command prints it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "gpu/float_probe.hpp"
#include "probe/cpu_float_probe.hpp"
#include "probe/float_cases.hpp"
#include "probe/float_profile.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
using probe::FloatProfile;
using probe::Rounding;

const FloatProfile& cpu_profile() {
    static const FloatProfile p = probe::summarize("cpu", probe::run_cpu_float_probe(probe::probe_cases()));
    return p;
}

// Lavapipe under the validation layer: any message makes run_vulkan_float_probe throw.
const DeviceProbeRun& lavapipe_run() {
    static const DeviceProbeRun run = [] {
        std::vector<DeviceProbeRun> runs = run_vulkan_float_probe(VulkanOptions{"lavapipe", true});
        EXPECT_EQ(runs.size(), 1u);
        return runs.at(0);
    }();
    return run;
}

TEST(FloatProfile, CpuSpecialCasesAreIeeeBinary32) {
    const FloatProfile& p = cpu_profile();
    // -ffp-contract=off: a*b and the sum are rounded separately, precise or not.
    EXPECT_EQ(p.product_sum, Rounding::Separate);
    EXPECT_EQ(p.product_sum_precise, Rounding::Separate);
    EXPECT_EQ(p.product_sum_value, 0x1p-11f);
    // Denormals are kept, whether an input or only the result is one.
    EXPECT_EQ(p.mul_tiny, 1e-40f);
    EXPECT_EQ(p.mul_half_min, 0x1p-127f);
    EXPECT_EQ(p.add_tiny, std::ldexp(1e-40f, 1));  // doubling is exact, denormal or not
    EXPECT_EQ(p.sub_normals, 0x1p-127f);
    EXPECT_EQ(p.pow_0_0, 1.0f);  // C's powf; GLSL leaves it undefined
    EXPECT_EQ(p.pow_0_1, 0.0f);
    EXPECT_EQ(p.one_over_neg_zero, -std::numeric_limits<float>::infinity());
    EXPECT_EQ(p.sqrt_neg_zero, 0.0f);
    EXPECT_TRUE(std::signbit(p.sqrt_neg_zero));
    EXPECT_TRUE(p.isnan_nan);
    EXPECT_FALSE(p.isinf_nan);
    EXPECT_FALSE(p.isnan_inf);
    EXPECT_TRUE(p.isinf_inf);
}

// GLM's min and max are `y < x ? y : x` and `x < y ? y : x`: a comparison with NaN is
// false, so the first argument comes back. IEEE 754 does not decide this for a
// comparison-based min; the row records what the reference does.
TEST(FloatProfile, CpuMinMaxWithNanReturnTheFirstArgument) {
    const FloatProfile& p = cpu_profile();
    EXPECT_TRUE(std::isnan(p.min_nan_first));
    EXPECT_EQ(p.min_nan_second, 1.0f);
    EXPECT_TRUE(std::isnan(p.max_nan_first));
    EXPECT_EQ(p.max_nan_second, 1.0f);
}

// Division and sqrt are correctly rounded on the CPU (SSE), so every result equals the
// double result rounded to float.
TEST(FloatProfile, CpuDivisionAndSqrtAreCorrectlyRounded) {
    const FloatProfile& p = cpu_profile();
    EXPECT_EQ(p.ulp_div, 0u);
    EXPECT_EQ(p.ulp_sqrt, 0u);
    EXPECT_LE(p.ulp_inversesqrt, 1u);  // 1 / sqrt(x): two roundings
    EXPECT_LE(p.ulp_unit_vector, 2u);
    EXPECT_LT(p.abs_sin, 1e-7);
    EXPECT_LT(p.abs_cos, 1e-7);
}

TEST(FloatProfile, LavapipeRunsTheProbeWithoutValidationMessages) {
    const DeviceProbeRun& run = lavapipe_run();
    EXPECT_NE(run.device.find("llvmpipe"), std::string::npos) << run.device;
    EXPECT_EQ(run.results.size(), probe::probe_cases().size());
}

// The spec bounds errors from the true value; the profile counts floats from the
// correctly rounded result, which is half a ULP from it at most: e ULP allowed is
// e + 0.5 floats at most, rounded down to a whole number of floats.
TEST(FloatProfile, LavapipeWithinTheVulkanPrecisionTable) {
    const FloatProfile p = probe::summarize(lavapipe_run().device, lavapipe_run().results);
    EXPECT_LE(p.ulp_div, 3u);          // OpFDiv: 2.5 ULP
    EXPECT_LE(p.ulp_inversesqrt, 2u);  // inversesqrt: 2 ULP
    EXPECT_LE(p.ulp_sqrt, 5u);         // sqrt: 1.0 / inversesqrt(), 2 + 2.5 ULP
    EXPECT_LE(p.ulp_exp2, 23u);        // exp2: 3 + 2|x| ULP, |x| <= 10
    EXPECT_LE(p.ulp_log2, 3u);         // log2 outside [0.5, 2]: 3 ULP
    EXPECT_LE(p.abs_sin, std::ldexp(1.0, -11));
    EXPECT_LE(p.abs_cos, std::ldexp(1.0, -11));
    // Required whatever the device: precise forbids the fused rounding, and a
    // division of a nonzero by zero is the signed infinity.
    EXPECT_EQ(p.product_sum_precise, Rounding::Separate);
    EXPECT_EQ(p.one_over_neg_zero, -std::numeric_limits<float>::infinity());
}

// The reason the kernel has unit_vector: it is bit-identical on both backends, case by
// case, not only as good in the worst case.
// normalize is counted too, as the contrast: on lavapipe it is not bit-identical, which
// is why the kernel does not use it (docs/crosscheck.md).
TEST(FloatProfile, UnitVectorIsBitIdenticalOnLavapipeAndCpu) {
    FloatProfile p = probe::summarize(lavapipe_run().device, lavapipe_run().results);
    probe::note_differences(p, lavapipe_run().results, probe::run_cpu_float_probe(probe::probe_cases()));
    EXPECT_EQ(p.unit_vector_differing, 0u);
    EXPECT_GT(p.normalize_differing, 0u);
}

// The numerical-stability suite, case 11: the kernel's random numbers are bit-identical on both backends for
// the same (pixel, sample, seed, dimension), extreme keys included, and stay in [0, 1)
// on both: the probe runs rng_next itself (rng.glsl) on lavapipe and on the CPU.
TEST(FloatProfile, RandomNumbersAreBitIdenticalAndBelowOne) {
    FloatProfile p = probe::summarize(lavapipe_run().device, lavapipe_run().results);
    probe::note_differences(p, lavapipe_run().results, probe::run_cpu_float_probe(probe::probe_cases()));
    EXPECT_EQ(p.rng_differing, 0u);
    EXPECT_EQ(p.rng_outside, 0u);
    EXPECT_LT(p.rng_largest, 1.0f);
    EXPECT_GT(p.rng_largest, 0.99f);  // 4,096 draws: the largest is near 1
    EXPECT_EQ(cpu_profile().rng_outside, 0u);
}

TEST(FloatProfile, FloatDistanceCountsFloatsBetween) {
    EXPECT_EQ(probe::float_distance(1.0f, 1.0f), 0u);
    EXPECT_EQ(probe::float_distance(0.0f, -0.0f), 0u);
    EXPECT_EQ(probe::float_distance(1.0f, std::nextafter(1.0f, 2.0f)), 1u);
    EXPECT_EQ(probe::float_distance(-std::numeric_limits<float>::denorm_min(),
                                    std::numeric_limits<float>::denorm_min()), 2u);
    EXPECT_EQ(probe::float_distance(std::nanf(""), 1.0f), std::numeric_limits<std::uint64_t>::max());
}

std::string read_file(const std::filesystem::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FloatProfile, CommandPrintsTheTableAndWritesJson) {
    const std::filesystem::path dir = test::temp_dir("float_profile_command");
    const std::filesystem::path json_file = dir / "profile.json";
    const test::ProgramRun run = test::run_vkrt(
        "devices --float-profile --device lavapipe --json " + test::shell_quote(json_file.string()), dir);
    EXPECT_EQ(run.code, 0) << run.stderr_text;
    const std::string out = read_file(dir / "stdout.txt");
    for (const char* piece : {"property", "cpu", "llvmpipe", "Vulkan spec", "a*b+c, precise", "2^-126 * 0.5",
                              "pow(0, 0)", "1 / -0.0", "sqrt(-0.0)", "x / y, max ULP", "unit_vector (ray.glsl)", "unit_vector, cases differing from cpu",
                              "rng_next (rng.glsl), largest value", "rng_next, cases differing from cpu",
                              "cos on [-pi, pi], max abs error"}) {
        EXPECT_NE(out.find(piece), std::string::npos) << piece << "\n" << out;
    }
    const nlohmann::json json = nlohmann::json::parse(read_file(json_file));
    ASSERT_EQ(json.at("columns").size(), 2u);
    const nlohmann::json& cpu = json["columns"][0];
    EXPECT_EQ(cpu.at("name"), "cpu");
    EXPECT_EQ(cpu.at("max_ulp").at("div"), 0);
    EXPECT_EQ(cpu.at("one_over_neg_zero"), "-inf");
    EXPECT_EQ(cpu.at("mul_denormal_input"), "1e-40");
    EXPECT_EQ(cpu.at("product_sum_fused"), false);
    // The random numbers (case 11): the device column names how many differ from the CPU's.
    EXPECT_EQ(cpu.at("rng_next").at("outside_unit_interval"), 0);
    EXPECT_LT(std::stof(cpu.at("rng_next").at("largest").get<std::string>()), 1.0f);
    EXPECT_EQ(json["columns"][1].at("differing_from_cpu").at("rng_next"), 0);
    EXPECT_EQ(json["columns"][1].at("differing_from_cpu").at("unit_vector"), 0);
    EXPECT_NE(json["columns"][1].at("name").get<std::string>().find("llvmpipe"), std::string::npos);
}

// Standard error without its final newline: the whole of it must be one line.
std::string without_newline(std::string text) {
    if (!text.empty() && text.back() == '\n') text.pop_back();
    return text;
}

TEST(FloatProfile, CommandRefusesAnUnknownDevice) {
    const std::filesystem::path dir = test::temp_dir("float_profile_bad_device");
    const test::ProgramRun run = test::run_vkrt("devices --float-profile --device no-such-gpu", dir);
    EXPECT_EQ(run.code, 1);
    test::expect_error_message(without_newline(run.stderr_text), "error: no Vulkan device matches 'no-such-gpu'", {"available"});
    const test::ProgramRun lone = test::run_vkrt("devices --device lavapipe", dir);
    EXPECT_EQ(lone.code, 1);
    test::expect_error_message(without_newline(lone.stderr_text), "error: --device requires --float-profile", {});
    const test::ProgramRun unwritable =
        test::run_vkrt("devices --float-profile --json " + test::shell_quote((dir / "no" / "such.json").string()), dir);
    EXPECT_EQ(unwritable.code, 1);
    test::expect_error_message(without_newline(unwritable.stderr_text), "error: ", {"cannot write the JSON file"});
}

}  // namespace
