#include "probe/float_profile_table.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <fmt/format.h>

#include "probe/float_cases.hpp"

namespace vkrt::probe {

namespace {

using probe::FloatProfile;
using probe::Rounding;

struct Row {
    std::string property;
    std::function<std::string(const FloatProfile&)> value;
    std::string spec;  // what the Vulkan spec allows, for the last column
};

std::string rounding(Rounding r, float value) {
    switch (r) {
    case Rounding::Separate: return "two roundings";
    case Rounding::Fused: return "fused";
    default: return fmt::format("neither: {:g}", value);
    }
}

// The value and whether it shows a denormal kept or flushed.
std::string denormal(float value) {
    return fmt::format("{:g} ({})", value, value == 0.0f ? "flushed" : "kept");
}

std::string yes_no(bool b) { return b ? "true" : "false"; }

std::string ulps(std::uint64_t u) {
    return u == std::numeric_limits<std::uint64_t>::max() ? "NaN" : fmt::format("{}", u);
}

std::vector<Row> rows() {
    return {
        {"a*b+c, no precise (a=b=1+2^-12, c=-1)",
         [](const FloatProfile& p) { return rounding(p.product_sum, p.product_sum_value); }, "either"},
        {"a*b+c, precise", [](const FloatProfile& p) { return rounding(p.product_sum_precise, p.product_sum_precise_value); },
         "two roundings"},
        {"1e-40 * 1", [](const FloatProfile& p) { return denormal(p.mul_tiny); }, "may flush"},
        {"2^-126 * 0.5", [](const FloatProfile& p) { return denormal(p.mul_half_min); }, "may flush"},
        {"1e-40 + 1e-40", [](const FloatProfile& p) { return denormal(p.add_tiny); }, "may flush"},
        {"1.5*2^-126 - 2^-126", [](const FloatProfile& p) { return denormal(p.sub_normals); }, "may flush"},
        {"pow(0, 0)", [](const FloatProfile& p) { return fmt::format("{:g}", p.pow_0_0); }, "undefined"},
        {"pow(0, 1)", [](const FloatProfile& p) { return fmt::format("{:g}", p.pow_0_1); }, "exp2(1*log2(0))"},
        {"1 / -0.0", [](const FloatProfile& p) { return fmt::format("{:g}", p.one_over_neg_zero); }, "-inf"},
        {"sqrt(-0.0)", [](const FloatProfile& p) { return fmt::format("{:g}", p.sqrt_neg_zero); }, "-0 (IEEE)"},
        {"min(NaN, 1), min(1, NaN)",
         [](const FloatProfile& p) { return fmt::format("{:g}, {:g}", p.min_nan_first, p.min_nan_second); },
         "undefined"},
        {"max(NaN, 1), max(1, NaN)",
         [](const FloatProfile& p) { return fmt::format("{:g}, {:g}", p.max_nan_first, p.max_nan_second); },
         "undefined"},
        {"isnan(NaN), isinf(NaN)",
         [](const FloatProfile& p) { return yes_no(p.isnan_nan) + ", " + yes_no(p.isinf_nan); }, "true, false"},
        {"isnan(inf), isinf(inf)",
         [](const FloatProfile& p) { return yes_no(p.isnan_inf) + ", " + yes_no(p.isinf_inf); }, "false, true"},
        {"x / y, max ULP", [](const FloatProfile& p) { return ulps(p.ulp_div); }, "2.5"},
        {"sqrt, max ULP", [](const FloatProfile& p) { return ulps(p.ulp_sqrt); }, "1/inversesqrt: 4.5"},
        {"inversesqrt, max ULP", [](const FloatProfile& p) { return ulps(p.ulp_inversesqrt); }, "2"},
        {"normalize, max ULP", [](const FloatProfile& p) { return ulps(p.ulp_normalize); }, "x / length(x)"},
        {"length, max ULP", [](const FloatProfile& p) { return ulps(p.ulp_length); }, "sqrt(dot(x, x))"},
        {"unit_vector (ray.glsl), max ULP", [](const FloatProfile& p) { return ulps(p.ulp_unit_vector); },
         "x / sqrt(dot(x, x))"},
        {"normalize, cases differing from cpu",
         [](const FloatProfile& p) { return fmt::format("{} of {}", p.normalize_differing, probe::kProbeSamples); },
         ""},
        {"unit_vector, cases differing from cpu",
         [](const FloatProfile& p) { return fmt::format("{} of {}", p.unit_vector_differing, probe::kProbeSamples); },
         ""},
        {"rng_next (rng.glsl), largest value", [](const FloatProfile& p) { return fmt::format("{:.9g}", p.rng_largest); },
         ""},
        {"rng_next, values outside [0, 1)",
         [](const FloatProfile& p) { return fmt::format("{} of {}", p.rng_outside, probe::kProbeSamples); }, ""},
        {"rng_next, cases differing from cpu",
         [](const FloatProfile& p) { return fmt::format("{} of {}", p.rng_differing, probe::kProbeSamples); }, ""},
        {"exp2 on [-10, 10], max ULP", [](const FloatProfile& p) { return ulps(p.ulp_exp2); }, "3 + 2|x|: 23"},
        {"log2 outside [0.5, 2], max ULP", [](const FloatProfile& p) { return ulps(p.ulp_log2); }, "3"},
        {"sin on [-pi, pi], max abs error", [](const FloatProfile& p) { return fmt::format("{:.2g}", p.abs_sin); },
         "2^-11 = 4.9e-04"},
        {"cos on [-pi, pi], max abs error", [](const FloatProfile& p) { return fmt::format("{:.2g}", p.abs_cos); },
         "2^-11 = 4.9e-04"},
    };
}

}  // namespace

std::string float_profile_table(const std::vector<FloatProfile>& columns) {
    const std::vector<Row> all = rows();
    // Cells first, then the widths, so every column lines up.
    std::vector<std::vector<std::string>> cells;
    std::vector<std::string> header{"property"};
    for (const FloatProfile& p : columns) header.push_back(p.name);
    header.push_back("Vulkan spec");
    cells.push_back(header);
    for (const Row& r : all) {
        std::vector<std::string> line{r.property};
        for (const FloatProfile& p : columns) line.push_back(r.value(p));
        line.push_back(r.spec);
        cells.push_back(line);
    }
    std::vector<std::size_t> width(header.size(), 0);
    for (const auto& line : cells) {
        for (std::size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
    }
    std::string out;
    for (const auto& line : cells) {
        std::string text;
        for (std::size_t c = 0; c < line.size(); ++c) {
            text += c + 1 < line.size() ? fmt::format("{:<{}}  ", line[c], width[c]) : line[c];
        }
        text.erase(text.find_last_not_of(' ') + 1);  // a row with an empty last cell
        out += text + "\n";
    }
    return out;
}

}  // namespace vkrt::probe
