#pragma once
// The inputs of the float probe (`vkrt devices --float-profile`, docs/numerics.md):
// a list of (operation, argument) cases, the same for the CPU and every device, so
// that their results can be compared case by case. First the special cases, one each,
// then kProbeSamples inputs for each measured function.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace vkrt::probe {

using uint = std::uint32_t;
#include "probe/float_op_ids.glsl"

// One case as shaders/float_probe.comp reads it (std430: two 16-byte members).
struct ProbeCase {
    glm::vec4 arg{0.0f};
    glm::uvec4 op{0u};
};
static_assert(sizeof(ProbeCase) == 32);

// The special cases, in their order at the start of the list.
enum class Special : std::size_t {
    ProductSum,         // (1 + 2^-12)^2 - 1: fused and two roundings differ
    ProductSumPrecise,  // the same under `precise`
    MulTiny,            // 1e-40 * 1: a denormal input
    MulHalfMin,         // 2^-126 * 0.5: normal inputs, a denormal result
    AddTiny,            // 1e-40 + 1e-40
    SubNormals,         // 1.5 * 2^-126 - 2^-126: normal inputs, a denormal result
    Pow00,              // pow(0, 0), undefined in GLSL
    Pow01,              // pow(0, 1)
    OneOverNegZero,     // 1 / -0
    SqrtNegZero,        // sqrt(-0)
    MinNanFirst,        // min(NaN, 1)
    MinNanSecond,       // min(1, NaN)
    MaxNanFirst,        // max(NaN, 1)
    MaxNanSecond,       // max(1, NaN)
    ClassifyNan,        // (isnan, isinf) of NaN
    ClassifyInf,        // (isnan, isinf) of +inf
    Count
};

// The functions whose error is measured, each over kProbeSamples inputs.
enum class Measured : std::size_t {
    Div, Sqrt, InverseSqrt, Normalize, Length, UnitVector, Exp2, Log2, Sin, Cos,
    Rng,  // not an error: rng_next's values, compared bit for bit with the CPU's
    Count
};

inline constexpr std::size_t kSpecialCount = static_cast<std::size_t>(Special::Count);
inline constexpr std::size_t kMeasuredCount = static_cast<std::size_t>(Measured::Count);
// Enough inputs that a function's bad corner shows, few enough to run in well under a
// second on lavapipe.
inline constexpr std::size_t kProbeSamples = 4096;

// The whole list: kSpecialCount + kMeasuredCount * kProbeSamples cases, always the same
// (the inputs come from a fixed hash sequence).
std::vector<ProbeCase> probe_cases();

inline std::size_t case_index(Special s) { return static_cast<std::size_t>(s); }
// The index of the first of `m`'s kProbeSamples cases.
inline std::size_t first_case(Measured m) {
    return kSpecialCount + static_cast<std::size_t>(m) * kProbeSamples;
}

}  // namespace vkrt::probe
