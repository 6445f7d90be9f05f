#pragma once
// What the float probe's results say about one column (the CPU or a device): how it
// rounds a*b+c, whether it keeps denormals, its special values, and the largest error
// of its built-in functions against double precision (docs/numerics.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace vkrt::probe {

enum class Rounding {
    Separate,  // a*b rounded, then the sum rounded: what -ffp-contract=off does
    Fused,     // one rounding, as fma(a, b, c)
    Other,     // neither: the value is in `product_sum`
};

struct FloatProfile {
    std::string name;  // "cpu" or the device's name

    Rounding product_sum = Rounding::Other;          // x * y + z in GLSL without `precise`
    Rounding product_sum_precise = Rounding::Other;  // the same under `precise`
    float product_sum_value = 0.0f;
    float product_sum_precise_value = 0.0f;

    // The results of denormal arithmetic; 0 where the column flushes denormals.
    float mul_tiny = 0.0f;      // 1e-40 * 1
    float mul_half_min = 0.0f;  // 2^-126 * 0.5
    float add_tiny = 0.0f;      // 1e-40 + 1e-40
    float sub_normals = 0.0f;   // 1.5 * 2^-126 - 2^-126

    float pow_0_0 = 0.0f;
    float pow_0_1 = 0.0f;
    float one_over_neg_zero = 0.0f;
    float sqrt_neg_zero = 0.0f;
    float min_nan_first = 0.0f;   // min(NaN, 1)
    float min_nan_second = 0.0f;  // min(1, NaN)
    float max_nan_first = 0.0f;   // max(NaN, 1)
    float max_nan_second = 0.0f;  // max(1, NaN)
    bool isnan_nan = false, isinf_nan = false, isnan_inf = false, isinf_inf = false;

    // Largest distance, in floats, from the correctly rounded result (the double
    // result rounded to float) over kProbeSamples inputs; vectors: over components.
    // A correctly rounded function scores 0; one within e ULP of the true value
    // scores at most e + 0.5.
    std::uint64_t ulp_div = 0, ulp_sqrt = 0, ulp_inversesqrt = 0, ulp_normalize = 0, ulp_length = 0,
                  ulp_unit_vector = 0, ulp_exp2 = 0, ulp_log2 = 0;
    // Largest absolute error over [-pi, pi].
    double abs_sin = 0.0, abs_cos = 0.0;

    // Of normalize's and unit_vector's kProbeSamples cases, how many differ in any bit
    // from the CPU column's (note_differences): a worst case can match while the
    // values do not, and it is the values that must agree for bit-identical backends.
    std::size_t normalize_differing = 0, unit_vector_differing = 0;

    // The kernel's random numbers (rng.glsl) over kProbeSamples streams: the largest
    // value, how many are outside [0, 1) (NaN included), and (note_differences) how
    // many differ from the CPU's in any bit: none, for the backends to sample alike.
    float rng_largest = 0.0f;
    std::size_t rng_outside = 0;
    std::size_t rng_differing = 0;
};

// Reads a column's results: one vec4 per case of probe_cases(), in its order.
FloatProfile summarize(std::string name, const std::vector<glm::vec4>& results);

// Fills the *_differing counts of `profile` from its results and the CPU's.
void note_differences(FloatProfile& profile, const std::vector<glm::vec4>& results,
                      const std::vector<glm::vec4>& cpu_results);

// The number of floats between a and b (0 when equal, +0 and -0 included); a NaN on
// either side is as far as it gets.
std::uint64_t float_distance(float a, float b);

}  // namespace vkrt::probe
