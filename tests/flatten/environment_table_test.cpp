// The environment as the kernel reads it (host/flatten/environment_table.cpp): the
// frame that turns world directions into the image's, the per-texel weights by
// which directions are drawn (the 1/8, 3/4, 1/8 neighbourhood of bilinear
// interpolation, longitude wrapping, latitude clamped, times the row's sine), and
// the words appended for the kernel: header, texels, and cumulative distributions.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "flatten/environment_table.hpp"
#include "scene/environment.hpp"

namespace {

using namespace vkrt;
using glm::dvec3;

constexpr double kPi = std::numbers::pi;

// A w x h environment, every texel `fill`.
Environment environment(std::uint32_t w, std::uint32_t h, glm::vec4 fill = glm::vec4(0.0f)) {
    Environment env;
    env.image.width = w;
    env.image.height = h;
    env.image.texels.assign(std::size_t(w) * h, fill);
    return env;
}

glm::vec4& texel(Environment& env, std::uint32_t x, std::uint32_t y) {
    return env.image.texels[std::size_t(y) * env.image.width + x];
}

std::uint32_t bits(float v) { return std::bit_cast<std::uint32_t>(v); }

void expect_near(const dvec3& got, const dvec3& want, double tolerance) {
    EXPECT_LE(glm::length(got - want), tolerance) << "got (" << got.x << ", " << got.y << ", " << got.z
                                                  << "), want (" << want.x << ", " << want.y << ", " << want.z << ")";
}

TEST(EnvironmentFrame, UpAndRotationTurnTheImage) {
    Environment env = environment(1, 1);
    EXPECT_EQ(environment_frame(env), glm::dmat3(1.0));
    // Turned right-handed about +y by 90 degrees: what the image shows along its +x
    // is seen along world -z.
    env.rotation = 90.0;
    expect_near(environment_frame(env) * dvec3(0, 0, -1), dvec3(1, 0, 0), 1e-15);
    expect_near(environment_frame(env) * dvec3(1, 0, 0), dvec3(0, 0, 1), 1e-15);
    // Up +z (of any length): the top row looks along world +z, and the image's +z
    // along world -y.
    env.rotation = 0.0;
    env.up = dvec3(0, 0, 2);
    EXPECT_EQ(environment_frame(env) * dvec3(0, 0, 1), dvec3(0, 1, 0));
    EXPECT_EQ(environment_frame(env) * dvec3(0, -1, 0), dvec3(0, 0, 1));
    EXPECT_EQ(environment_frame(env) * dvec3(1, 0, 0), dvec3(1, 0, 0));
    // Upside down, the one up the shortest rotation cannot reach by its formula.
    env.up = dvec3(0, -1, 0);
    EXPECT_EQ(environment_frame(env) * dvec3(0, -1, 0), dvec3(0, 1, 0));
    // Always a rotation.
    env.up = dvec3(0.3, -0.5, 0.8);
    env.rotation = 37.0;
    const glm::dmat3 m = environment_frame(env);
    expect_near(m * glm::normalize(env.up), dvec3(0, 1, 0), 1e-15);
    EXPECT_NEAR(glm::determinant(m), 1.0, 1e-15);
    const glm::dmat3 mtm = glm::transpose(m) * m;
    for (int i = 0; i < 3; ++i) expect_near(mtm[i], glm::dmat3(1.0)[i], 1e-15);
}

TEST(EnvironmentWeights, AConstantImageWeighsEachRowByItsSine) {
    const std::uint32_t w = 3, h = 4;
    const std::vector<double> weights = environment_weights(environment(w, h, glm::vec4(2.0f, 2.0f, 2.0f, 1.0f)));
    ASSERT_EQ(weights.size(), std::size_t(w) * h);
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) {
            EXPECT_NEAR(weights[y * w + x], 2.0 * std::sin(kPi * (y + 0.5) / h), 1e-15) << x << ", " << y;
        }
    }
}

TEST(EnvironmentWeights, LuminanceSpreadsOverTheNeighbourhood) {
    // One green texel at (0, 1) of a 4 x 3 image: its luminance is 0.7152 and it
    // reaches the columns either side (3 by wrapping) and the rows above and below.
    Environment env = environment(4, 3);
    texel(env, 0, 1) = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
    const std::vector<double> weights = environment_weights(env);
    const double lum = 0.7152;
    const double x_tap[4] = {0.75, 0.125, 0.0, 0.125};   // columns 0 to 3
    const double y_tap[3] = {0.125, 0.75, 0.125};        // rows 0 to 2
    const double sine[3] = {0.5, 1.0, 0.5};              // sin(pi/6), sin(pi/2), sin(5 pi/6)
    for (std::uint32_t y = 0; y < 3; ++y) {
        for (std::uint32_t x = 0; x < 4; ++x) {
            EXPECT_NEAR(weights[y * 4 + x], lum * x_tap[x] * y_tap[y] * sine[y], 1e-15) << x << ", " << y;
        }
    }
    // Red and blue count as little as Rec. 709 luminance says.
    Environment red = environment(1, 1, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    Environment blue = environment(1, 1, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    EXPECT_NEAR(environment_weights(red)[0], 0.2126, 1e-15);
    EXPECT_NEAR(environment_weights(blue)[0], 0.0722, 1e-15);
}

TEST(EnvironmentWeights, LatitudeStopsAtThePoles) {
    // A bright texel in the top row: the row above it is itself again.
    Environment env = environment(4, 3);
    texel(env, 1, 0) = glm::vec4(1.0f);
    const std::vector<double> weights = environment_weights(env);
    EXPECT_NEAR(weights[1], 0.75 * (0.75 + 0.125) * 0.5, 1e-15);
    EXPECT_NEAR(weights[4 + 1], 0.75 * 0.125 * 1.0, 1e-15);
    EXPECT_EQ(weights[8 + 1], 0.0) << "two rows down: out of reach";
}

TEST(AppendEnvironment, HeaderTexelsAndDistributions) {
    // 2 x 3: the top row white, the others black. The bilinear neighbourhood takes
    // 7/8 of the top row's weight into it and 1/8 into the middle row; the bottom
    // row gets none.
    Environment env = environment(2, 3);
    texel(env, 0, 0) = texel(env, 1, 0) = glm::vec4(0.5f, 1.0f, 1.5f, 1.0f);
    env.intensity = 2.0;
    std::vector<std::uint32_t> words(5, 0xDEADu);  // what was there before stays
    bool sampled = false;
    const std::uint32_t first = append_environment(env, words, sampled);
    EXPECT_EQ(first, 5u);
    EXPECT_TRUE(sampled);
    const std::vector<std::uint32_t> header(words.begin() + first, words.begin() + first + 12);
    // The frame row by row (the identity here), the size, and a zero.
    EXPECT_EQ(header, (std::vector<std::uint32_t>{bits(1.0f), 0, 0, 0, bits(1.0f), 0, 0, 0, bits(1.0f), 2, 3, 0}));
    // The texels' rgb times the intensity.
    std::size_t at = first + 12;
    for (std::uint32_t i = 0; i < 6; ++i) {
        const bool white = i < 2;
        EXPECT_EQ(words[at++], bits(white ? 1.0f : 0.0f)) << "texel " << i;
        EXPECT_EQ(words[at++], bits(white ? 2.0f : 0.0f)) << "texel " << i;
        EXPECT_EQ(words[at++], bits(white ? 3.0f : 0.0f)) << "texel " << i;
    }
    // The rows' cumulative distribution: the middle row's sine is twice the top's,
    // so its 1/8 weighs 2/9 against the top's 7/8 * 1/2.
    const float top = float((0.875 * 0.5) / (0.875 * 0.5 + 0.125 * 1.0));
    EXPECT_EQ(words[at++], bits(top));
    EXPECT_EQ(words[at++], bits(1.0f));
    EXPECT_EQ(words[at++], bits(1.0f)) << "the last entry is exactly 1";
    // Within each row, its texels' distribution: even, and even for the black row
    // too (never drawn, but a search through it must end).
    for (std::uint32_t row = 0; row < 3; ++row) {
        EXPECT_EQ(words[at++], bits(0.5f)) << "row " << row;
        EXPECT_EQ(words[at++], bits(1.0f)) << "row " << row;
    }
    EXPECT_EQ(at, words.size());
}

TEST(AppendEnvironment, ABlackOrDarkenedImageIsNeverSampled) {
    std::vector<std::uint32_t> words;
    bool sampled = true;
    append_environment(environment(4, 2), words, sampled);
    EXPECT_FALSE(sampled) << "black";
    Environment off = environment(4, 2, glm::vec4(1.0f));
    off.intensity = 0.0;
    sampled = true;
    append_environment(off, words, sampled);
    EXPECT_FALSE(sampled) << "intensity 0";
}

}  // namespace
