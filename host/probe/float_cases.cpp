#include "probe/float_cases.hpp"

#include <cmath>
#include <limits>

namespace vkrt::probe {

namespace {

// A counter-based hash (the finalizer of SplitMix64): the same inputs on every run
// and every machine, without a random engine whose sequence the library may change.
std::uint64_t mix(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// Uniform in [0, 1) with 24 bits, so that every value is exactly a float.
float unit(std::uint64_t key) {
    return static_cast<float>(mix(key) >> 40) * 0x1p-24f;
}

// A float of random sign, significand and binary exponent in [lo, hi]: every binade of
// the range is sampled alike, not just the largest.
float spread(std::uint64_t key, int lo, int hi, bool signed_too) {
    const float significand = 1.0f + unit(key);
    const int exponent = lo + static_cast<int>(mix(key ^ 0xABCDu) % static_cast<std::uint64_t>(hi - lo + 1));
    const float magnitude = std::ldexp(significand, exponent);
    return signed_too && (mix(key ^ 0x5151u) & 1u) ? -magnitude : magnitude;
}

ProbeCase make(uint op, float x, float y = 0.0f, float z = 0.0f) {
    return ProbeCase{glm::vec4(x, y, z, 0.0f), glm::uvec4(op, 0u, 0u, 0u)};
}

// A stream of the kernel's random numbers: pixel, sample and seed from the hash, every
// eighth of them at an extreme (0 or 2^32 - 1), and a dimension below 64 (exact as a
// float argument).
ProbeCase random_stream(std::uint64_t key) {
    auto word = [&](std::uint64_t salt) {
        const std::uint64_t h = mix(key ^ salt);
        return (h & 7u) == 0 ? ((h >> 3) & 1u ? 0xFFFFFFFFu : 0u) : static_cast<uint>(h >> 32);
    };
    ProbeCase c = make(FLOAT_OP_RNG, static_cast<float>(mix(key ^ 0xD1u) % 64u));
    c.op = glm::uvec4(FLOAT_OP_RNG, word(0xA1u), word(0xB2u), word(0xC3u));
    return c;
}

ProbeCase sample(Measured m, std::uint64_t i) {
    const std::uint64_t key = (static_cast<std::uint64_t>(m) << 32) | i;
    const float pi = 3.14159265358979f;
    switch (m) {
    // Divisors well inside the [2^-126, 2^126] where the spec bounds division.
    case Measured::Div: return make(FLOAT_OP_DIV, spread(key, -20, 20, true), spread(key + 7, -20, 20, true));
    case Measured::Sqrt: return make(FLOAT_OP_SQRT, spread(key, -40, 40, false));
    case Measured::InverseSqrt: return make(FLOAT_OP_INVERSESQRT, spread(key, -40, 40, false));
    case Measured::Exp2: return make(FLOAT_OP_EXP2, 20.0f * unit(key) - 10.0f);
    // Outside [0.5, 2], where the spec bounds log2 in ULPs (inside, absolutely).
    case Measured::Log2: {
        const bool small = mix(key ^ 0x77u) & 1u;
        return make(FLOAT_OP_LOG2, small ? spread(key, -30, -2, false) : spread(key, 1, 30, false));
    }
    case Measured::Sin: return make(FLOAT_OP_SIN, (2.0f * unit(key) - 1.0f) * pi);
    case Measured::Cos: return make(FLOAT_OP_COS, (2.0f * unit(key) - 1.0f) * pi);
    case Measured::Rng: return random_stream(key);
    default: break;
    }
    // Vectors: components in [-1, 1) times one common power of two, as directions and
    // normals of any scene scale are.
    const float scale = std::ldexp(1.0f, static_cast<int>(mix(key ^ 0x99u) % 17u) - 8);
    const float x = (2.0f * unit(key * 3 + 1) - 1.0f) * scale;
    const float y = (2.0f * unit(key * 3 + 2) - 1.0f) * scale;
    const float z = (2.0f * unit(key * 3 + 3) - 1.0f) * scale;
    const uint op = m == Measured::Normalize ? FLOAT_OP_NORMALIZE
                    : m == Measured::Length  ? FLOAT_OP_LENGTH
                                             : FLOAT_OP_UNIT_VECTOR;
    return make(op, x, y, z);
}

}  // namespace

std::vector<ProbeCase> probe_cases() {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const float a = 1.0f + 0x1p-12f;
    std::vector<ProbeCase> cases(kSpecialCount);
    cases[case_index(Special::ProductSum)] = make(FLOAT_OP_PRODUCT_SUM, a, a, -1.0f);
    cases[case_index(Special::ProductSumPrecise)] = make(FLOAT_OP_PRODUCT_SUM_PRECISE, a, a, -1.0f);
    cases[case_index(Special::MulTiny)] = make(FLOAT_OP_MUL, 1e-40f, 1.0f);
    cases[case_index(Special::MulHalfMin)] = make(FLOAT_OP_MUL, 0x1p-126f, 0.5f);
    cases[case_index(Special::AddTiny)] = make(FLOAT_OP_ADD, 1e-40f, 1e-40f);
    cases[case_index(Special::SubNormals)] = make(FLOAT_OP_ADD, 0x1.8p-126f, -0x1p-126f);
    cases[case_index(Special::Pow00)] = make(FLOAT_OP_POW, 0.0f, 0.0f);
    cases[case_index(Special::Pow01)] = make(FLOAT_OP_POW, 0.0f, 1.0f);
    cases[case_index(Special::OneOverNegZero)] = make(FLOAT_OP_DIV, 1.0f, -0.0f);
    cases[case_index(Special::SqrtNegZero)] = make(FLOAT_OP_SQRT, -0.0f);
    cases[case_index(Special::MinNanFirst)] = make(FLOAT_OP_MIN, nan, 1.0f);
    cases[case_index(Special::MinNanSecond)] = make(FLOAT_OP_MIN, 1.0f, nan);
    cases[case_index(Special::MaxNanFirst)] = make(FLOAT_OP_MAX, nan, 1.0f);
    cases[case_index(Special::MaxNanSecond)] = make(FLOAT_OP_MAX, 1.0f, nan);
    cases[case_index(Special::ClassifyNan)] = make(FLOAT_OP_CLASSIFY, nan);
    cases[case_index(Special::ClassifyInf)] = make(FLOAT_OP_CLASSIFY, inf);
    for (std::size_t m = 0; m < kMeasuredCount; ++m) {
        for (std::size_t i = 0; i < kProbeSamples; ++i) {
            cases.push_back(sample(static_cast<Measured>(m), i));
        }
    }
    return cases;
}

}  // namespace vkrt::probe
