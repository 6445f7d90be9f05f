#include "probe/float_profile_json.hpp"

#include <fmt/format.h>

#include "probe/float_cases.hpp"

namespace vkrt::probe {

namespace {

using probe::FloatProfile;
using probe::Rounding;

// The shortest text that reads back as the same float.
std::string value(float f) { return fmt::format("{}", f); }

bool fused(Rounding r) { return r == Rounding::Fused; }

nlohmann::json column(const FloatProfile& p) {
    return {
        {"name", p.name},
        // null when the result was neither of the two roundings
        {"product_sum_fused", p.product_sum == Rounding::Other ? nlohmann::json() : nlohmann::json(fused(p.product_sum))},
        {"product_sum_precise_fused", p.product_sum_precise == Rounding::Other
                                          ? nlohmann::json()
                                          : nlohmann::json(fused(p.product_sum_precise))},
        {"product_sum", value(p.product_sum_value)},
        {"product_sum_precise", value(p.product_sum_precise_value)},
        {"mul_denormal_input", value(p.mul_tiny)},
        {"mul_denormal_result", value(p.mul_half_min)},
        {"add_denormal_input", value(p.add_tiny)},
        {"add_denormal_result", value(p.sub_normals)},
        {"pow_0_0", value(p.pow_0_0)},
        {"pow_0_1", value(p.pow_0_1)},
        {"one_over_neg_zero", value(p.one_over_neg_zero)},
        {"sqrt_neg_zero", value(p.sqrt_neg_zero)},
        {"min_nan_1", value(p.min_nan_first)},
        {"min_1_nan", value(p.min_nan_second)},
        {"max_nan_1", value(p.max_nan_first)},
        {"max_1_nan", value(p.max_nan_second)},
        {"isnan_nan", p.isnan_nan},
        {"isinf_nan", p.isinf_nan},
        {"isnan_inf", p.isnan_inf},
        {"isinf_inf", p.isinf_inf},
        {"max_ulp",
         {{"div", p.ulp_div},
          {"sqrt", p.ulp_sqrt},
          {"inversesqrt", p.ulp_inversesqrt},
          {"normalize", p.ulp_normalize},
          {"length", p.ulp_length},
          {"unit_vector", p.ulp_unit_vector},
          {"exp2", p.ulp_exp2},
          {"log2", p.ulp_log2}}},
        {"max_abs_error", {{"sin", p.abs_sin}, {"cos", p.abs_cos}}},
        {"differing_from_cpu",
         {{"normalize", p.normalize_differing}, {"unit_vector", p.unit_vector_differing}, {"rng_next", p.rng_differing}}},
        {"rng_next", {{"largest", value(p.rng_largest)}, {"outside_unit_interval", p.rng_outside}}},
    };
}

}  // namespace

nlohmann::json float_profile_json(const std::vector<FloatProfile>& columns) {
    nlohmann::json out = {{"samples_per_function", probe::kProbeSamples}, {"columns", nlohmann::json::array()}};
    for (const FloatProfile& p : columns) out["columns"].push_back(column(p));
    return out;
}

}  // namespace vkrt::probe
