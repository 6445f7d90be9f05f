// The samplers of render.sampler (shaders/kernel/rng.glsl, sampler.glsl): the
// Owen-scrambled Sobol points against their defining properties, computed here
// independently, and the hash sampler against the hash.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::Kernel;
using vkrt::kernel::uint;
using vkrt::kernel::vec2;

Kernel kernel_with(uint sampler) {
    Kernel k;
    vkrt::kernel::set_sampler_kind(k.params, sampler);
    return k;
}

std::uint32_t reverse_bits(std::uint32_t x) {
    std::uint32_t r = 0;
    for (int i = 0; i < 32; ++i) r |= ((x >> i) & 1u) << (31 - i);
    return r;
}

// Sobol's second dimension from its definition (Bratley & Fox 1988): primitive
// polynomial x + 1, initial m_1 = 1, recurrence m_k = 2 m_{k-1} xor m_{k-1}, direction
// numbers v_k = m_k / 2^k, point = xor of the v_k of the index's set bits.
std::uint32_t sobol_second(std::uint32_t index) {
    std::uint32_t m = 1;
    std::uint32_t x = 0;
    for (int k = 1; k <= 32; ++k) {
        if ((index >> (k - 1)) & 1u) x ^= m << (32 - k);
        m = (m << 1) ^ m;
    }
    return x;
}

TEST(SobolSampler, SecondDimensionMatchesItsDirectionNumbers) {
    Kernel k;
    std::mt19937 rng(3);
    for (std::uint32_t i = 0; i < 70000; ++i) {
        const std::uint32_t index = i < 4096 ? i : rng();
        ASSERT_EQ(reverse_bits(k.sobol_second_reversed(index)), sobol_second(index)) << index;
    }
}

// The permutation's bit j depends on the bits 0..j of its input only, and each
// restriction to the low n bits is a bijection: what makes it a nested scramble.
TEST(SobolSampler, LaineKarrasPermutationIsNested) {
    Kernel k;
    std::mt19937 rng(4);
    for (int trial = 0; trial < 2000; ++trial) {
        const std::uint32_t x = rng();
        const std::uint32_t seed = rng();
        const int bit = int(rng() % 32);
        const std::uint32_t low = bit == 31 ? ~0u : (2u << bit) - 1u;
        const std::uint32_t flipped = x ^ (~low & rng());  // only bits above `bit` change
        ASSERT_EQ(k.laine_karras_permutation(x, seed) & low, k.laine_karras_permutation(flipped, seed) & low);
    }
    for (std::uint32_t seed : {0u, 1u, 0xdeadbeefu, 0x12345678u}) {
        std::vector<bool> seen(1u << 12, false);
        for (std::uint32_t x = 0; x < (1u << 12); ++x) seen[k.laine_karras_permutation(x, seed) & 0xfffu] = true;
        EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 1 << 12) << seed;
    }
}

// The 2^m points of samples [first, first + 2^m) of one slot, as the kernel draws them.
std::vector<vec2> slot_points(Kernel& k, uint pixel, uint seed, uint slot, uint first, uint m) {
    std::vector<vec2> points;
    for (uint s = first; s < first + (1u << m); ++s) {
        auto rng = k.rng_start(pixel, s, seed);
        k.rng_seek(rng, slot);
        points.push_back(k.rng_2d(rng));
    }
    return points;
}

// A (0, m, 2)-net: every elementary box of area 2^-m (2^a by 2^(m-a) cells) holds
// exactly one point.
void expect_net(const std::vector<vec2>& points, uint m) {
    for (uint a = 0; a <= m; ++a) {
        std::set<std::pair<uint, uint>> cells;
        for (const vec2& p : points) {
            ASSERT_GE(p.x, 0.0f);
            ASSERT_LT(p.x, 1.0f);
            ASSERT_GE(p.y, 0.0f);
            ASSERT_LT(p.y, 1.0f);
            cells.insert({uint(p.x * float(1u << a)), uint(p.y * float(1u << (m - a)))});
        }
        EXPECT_EQ(cells.size(), points.size()) << "boxes of 2^-" << a << " by 2^-" << (m - a);
    }
}

TEST(SobolSampler, EveryPowerOfTwoPrefixOfASlotIsANet) {
    Kernel k = kernel_with(vkrt::kernel::SAMPLER_SOBOL);
    for (uint pixel : {0u, 1u, 77777u}) {
        for (uint slot : {0u, 1u, 6u, 40u}) {
            for (uint m = 0; m <= 10; m += 2) {
                SCOPED_TRACE(testing::Message() << "pixel " << pixel << " slot " << slot << " 2^" << m);
                expect_net(slot_points(k, pixel, 9u, slot, 0u, m), m);
            }
            // Also any aligned block after the first: the samples of a later pass.
            expect_net(slot_points(k, pixel, 9u, slot, 3u << 8, 8u), 8u);
        }
    }
}

TEST(SobolSampler, OneNumberPerSlotIsStratifiedToo) {
    Kernel k = kernel_with(vkrt::kernel::SAMPLER_SOBOL);
    for (uint slot : {0u, 2u, 9u}) {
        std::set<uint> bins;
        for (uint s = 0; s < 1024; ++s) {
            auto rng = k.rng_start(5u, s, 1u);
            k.rng_seek(rng, slot);
            bins.insert(uint(k.rng_1d(rng) * 1024.0f));
        }
        EXPECT_EQ(bins.size(), 1024u) << "slot " << slot;
    }
}

// Slots and pixels are scrambled independently: no correlation between the numbers
// of two slots over a pixel's samples, nor between two pixels' same sample.
TEST(SobolSampler, SlotsAndPixelsDoNotCorrelate) {
    Kernel k = kernel_with(vkrt::kernel::SAMPLER_SOBOL);
    auto correlation = [](const std::vector<double>& a, const std::vector<double>& b) {
        double ma = 0, mb = 0;
        for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
        ma /= double(a.size());
        mb /= double(b.size());
        double ab = 0, aa = 0, bb = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            ab += (a[i] - ma) * (b[i] - mb);
            aa += (a[i] - ma) * (a[i] - ma);
            bb += (b[i] - mb) * (b[i] - mb);
        }
        return ab / std::sqrt(aa * bb);
    };
    constexpr int n = 4096;  // correlation of independent samples: sd 1/64
    for (auto [slot_a, slot_b] : {std::pair{1u, 2u}, std::pair{3u, 8u}, std::pair{0u, 5u}}) {
        std::vector<double> a, b;
        for (uint s = 0; s < n; ++s) {
            auto ra = k.rng_start(11u, s, 2u);
            auto rb = ra;
            k.rng_seek(ra, slot_a);
            k.rng_seek(rb, slot_b);
            a.push_back(k.rng_2d(ra).x);
            b.push_back(k.rng_2d(rb).y);
        }
        EXPECT_LT(std::abs(correlation(a, b)), 0.06) << slot_a << " " << slot_b;
    }
    std::vector<double> a, b;
    for (uint pixel = 0; pixel < n; ++pixel) {
        auto ra = k.rng_start(pixel, 0u, 2u);
        auto rb = k.rng_start(pixel + 1u, 0u, 2u);
        a.push_back(k.rng_1d(ra));
        b.push_back(k.rng_1d(rb));
    }
    EXPECT_LT(std::abs(correlation(a, b)), 0.06);
}

// Both samplers: the same (pixel, sample, seed, slot) gives the same number, and
// changing any one of them changes it.
TEST(Samplers, ArePureFunctionsOfPixelSampleSeedAndSlot) {
    for (uint sampler : {vkrt::kernel::SAMPLER_SOBOL, vkrt::kernel::SAMPLER_HASH}) {
        SCOPED_TRACE(sampler == vkrt::kernel::SAMPLER_SOBOL ? "sobol" : "hash");
        Kernel k = kernel_with(sampler);
        auto a = k.rng_start(3, 4, 5);
        auto b = k.rng_start(3, 4, 5);
        std::vector<float> drawn;
        for (int i = 0; i < 8; ++i) {
            const vec2 x = k.rng_2d(a);
            EXPECT_EQ(x, k.rng_2d(b));
            drawn.push_back(x.x);
        }
        auto c = k.rng_start(3, 4, 5);
        k.rng_seek(c, 5);
        EXPECT_EQ(k.rng_1d(c), drawn[5]);  // seeking lands where drawing in order does
        auto first = [&](uint p, uint s, uint seed) {
            auto r = k.rng_start(p, s, seed);
            return k.rng_1d(r);
        };
        std::set<float> values{first(3, 4, 5), first(4, 4, 5), first(3, 5, 5), first(3, 4, 6)};
        EXPECT_EQ(values.size(), 4u);
    }
}

// The hash sampler is the hash: a slot's one number is rng_next's, its pair the
// first two lanes of the same hash.
TEST(HashSampler, SlotsAreTheHashOfTheirCounters) {
    Kernel k = kernel_with(vkrt::kernel::SAMPLER_HASH);
    for (uint slot = 0; slot < 8; ++slot) {
        auto r = k.rng_start(12u, 34u, 56u);
        k.rng_seek(r, slot);
        auto next = r;
        const vec2 pair = k.rng_2d(r);
        EXPECT_EQ(pair.x, k.rng_next(next));
        const auto h = k.pcg4d({12u, 34u, 56u, slot});
        EXPECT_EQ(pair.y, k.unit_float(h.y));
        auto one = k.rng_start(12u, 34u, 56u);
        k.rng_seek(one, slot);
        EXPECT_EQ(k.rng_1d(one), pair.x);
        EXPECT_EQ(one.dim, slot + 1u);
    }
}

}  // namespace
