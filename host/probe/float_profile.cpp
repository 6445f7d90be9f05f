#include "probe/float_profile.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <utility>

#include "probe/float_cases.hpp"

namespace vkrt::probe {

namespace {

// The float bits as an integer that orders like the floats do (negative floats are
// sign-magnitude; this makes them two's complement), so -0 and +0 coincide.
std::int64_t ordered(float f) {
    const std::int32_t bits = std::bit_cast<std::int32_t>(f);
    return bits < 0 ? std::int64_t(std::numeric_limits<std::int32_t>::min()) - bits : bits;
}

Rounding rounding_of(float value, float x, float y, float z) {
    // Double holds the exact product of two floats, and fma the exact sum after it.
    const double exact = std::fma(double(x), double(y), double(z));
    const float fused = static_cast<float>(exact);
    const float separate = static_cast<float>(double(static_cast<float>(double(x) * double(y))) + double(z));
    if (value == separate && value != fused) return Rounding::Separate;
    if (value == fused && value != separate) return Rounding::Fused;
    return Rounding::Other;
}

// The double-precision value a measured case should approximate, for one component.
double reference(Measured m, const glm::vec4& a, int component) {
    const double x = a.x, y = a.y, z = a.z;
    const double len = std::sqrt(x * x + y * y + z * z);
    const double comp = component == 0 ? x : component == 1 ? y : z;
    switch (m) {
    case Measured::Div: return x / y;
    case Measured::Sqrt: return std::sqrt(x);
    case Measured::InverseSqrt: return 1.0 / std::sqrt(x);
    case Measured::Normalize:
    case Measured::UnitVector: return comp / len;
    case Measured::Length: return len;
    case Measured::Exp2: return std::exp2(x);
    case Measured::Log2: return std::log2(x);
    case Measured::Sin: return std::sin(x);
    case Measured::Cos: return std::cos(x);
    default: throw std::logic_error("float probe: no reference for this function");
    }
}

float lane(const glm::vec4& v, int component) {
    return component == 0 ? v.x : component == 1 ? v.y : v.z;
}

// The largest error of `m` over its cases: in floats from the correctly rounded
// result, or, for sin and cos, absolutely.
double largest_error(Measured m, const std::vector<ProbeCase>& cases, const std::vector<glm::vec4>& results) {
    const bool vector = m == Measured::Normalize || m == Measured::UnitVector;
    const bool absolute = m == Measured::Sin || m == Measured::Cos;
    double worst = 0.0;
    for (std::size_t i = first_case(m); i < first_case(m) + kProbeSamples; ++i) {
        for (int c = 0; c < (vector ? 3 : 1); ++c) {
            const double want = reference(m, cases[i].arg, c);
            const float got = lane(results[i], c);
            const double error = absolute ? std::abs(double(got) - want)
                                          : double(float_distance(got, static_cast<float>(want)));
            worst = std::isnan(got) ? std::numeric_limits<double>::infinity() : std::max(worst, error);
            if (std::isinf(worst)) return worst;
        }
    }
    return worst;
}

std::uint64_t largest_ulps(Measured m, const std::vector<ProbeCase>& cases, const std::vector<glm::vec4>& results) {
    const double e = largest_error(m, cases, results);
    return std::isinf(e) ? std::numeric_limits<std::uint64_t>::max() : static_cast<std::uint64_t>(e);
}

}  // namespace

std::uint64_t float_distance(float a, float b) {
    if (std::isnan(a) || std::isnan(b)) {
        return std::numeric_limits<std::uint64_t>::max();
    }
    const std::int64_t d = ordered(a) - ordered(b);
    return static_cast<std::uint64_t>(d < 0 ? -d : d);
}

void note_differences(FloatProfile& profile, const std::vector<glm::vec4>& results,
                      const std::vector<glm::vec4>& cpu_results) {
    if (results.size() != cpu_results.size()) {
        throw std::runtime_error("float probe: result lists of different lengths");
    }
    auto differing = [&](Measured m) {
        std::size_t n = 0;
        for (std::size_t i = first_case(m); i < first_case(m) + kProbeSamples; ++i) {
            n += std::bit_cast<glm::uvec4>(results[i]) != std::bit_cast<glm::uvec4>(cpu_results[i]);
        }
        return n;
    };
    profile.normalize_differing = differing(Measured::Normalize);
    profile.unit_vector_differing = differing(Measured::UnitVector);
    profile.rng_differing = differing(Measured::Rng);
}

FloatProfile summarize(std::string name, const std::vector<glm::vec4>& results) {
    const std::vector<ProbeCase> cases = probe_cases();
    if (results.size() != cases.size()) {
        throw std::runtime_error("float probe: " + std::to_string(results.size()) + " results for " +
                                 std::to_string(cases.size()) + " cases");
    }
    auto x_of = [&](Special s) { return results[case_index(s)].x; };
    FloatProfile p;
    p.name = std::move(name);
    const glm::vec4 ps = cases[case_index(Special::ProductSum)].arg;
    p.product_sum_value = x_of(Special::ProductSum);
    p.product_sum_precise_value = x_of(Special::ProductSumPrecise);
    p.product_sum = rounding_of(p.product_sum_value, ps.x, ps.y, ps.z);
    p.product_sum_precise = rounding_of(p.product_sum_precise_value, ps.x, ps.y, ps.z);
    p.mul_tiny = x_of(Special::MulTiny);
    p.mul_half_min = x_of(Special::MulHalfMin);
    p.add_tiny = x_of(Special::AddTiny);
    p.sub_normals = x_of(Special::SubNormals);
    p.pow_0_0 = x_of(Special::Pow00);
    p.pow_0_1 = x_of(Special::Pow01);
    p.one_over_neg_zero = x_of(Special::OneOverNegZero);
    p.sqrt_neg_zero = x_of(Special::SqrtNegZero);
    p.min_nan_first = x_of(Special::MinNanFirst);
    p.min_nan_second = x_of(Special::MinNanSecond);
    p.max_nan_first = x_of(Special::MaxNanFirst);
    p.max_nan_second = x_of(Special::MaxNanSecond);
    p.isnan_nan = results[case_index(Special::ClassifyNan)].x != 0.0f;
    p.isinf_nan = results[case_index(Special::ClassifyNan)].y != 0.0f;
    p.isnan_inf = results[case_index(Special::ClassifyInf)].x != 0.0f;
    p.isinf_inf = results[case_index(Special::ClassifyInf)].y != 0.0f;
    p.ulp_div = largest_ulps(Measured::Div, cases, results);
    p.ulp_sqrt = largest_ulps(Measured::Sqrt, cases, results);
    p.ulp_inversesqrt = largest_ulps(Measured::InverseSqrt, cases, results);
    p.ulp_normalize = largest_ulps(Measured::Normalize, cases, results);
    p.ulp_length = largest_ulps(Measured::Length, cases, results);
    p.ulp_unit_vector = largest_ulps(Measured::UnitVector, cases, results);
    p.ulp_exp2 = largest_ulps(Measured::Exp2, cases, results);
    p.ulp_log2 = largest_ulps(Measured::Log2, cases, results);
    p.abs_sin = largest_error(Measured::Sin, cases, results);
    p.abs_cos = largest_error(Measured::Cos, cases, results);
    for (std::size_t i = first_case(Measured::Rng); i < first_case(Measured::Rng) + kProbeSamples; ++i) {
        const float u = results[i].x;
        p.rng_largest = std::max(p.rng_largest, u);
        p.rng_outside += u >= 0.0f && u < 1.0f ? 0 : 1;  // a NaN is outside too
    }
    return p;
}

}  // namespace vkrt::probe
