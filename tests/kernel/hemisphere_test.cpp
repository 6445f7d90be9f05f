// Hemisphere sampling for global illumination (shaders/kernel/hemisphere.glsl): the
// orthonormal basis for every normal, poles and signed zeros included, and each way
// of drawing a direction against its stated density.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::Kernel;
using vkrt::kernel::vec3;

void expect_orthonormal(const Kernel::Basis& f, vec3 n) {
    SCOPED_TRACE(testing::Message() << "n = (" << n.x << ", " << n.y << ", " << n.z << ")");
    EXPECT_EQ(f.n, n);
    EXPECT_NEAR(glm::length(f.t), 1.0, 1e-6);
    EXPECT_NEAR(glm::length(f.b), 1.0, 1e-6);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.0, 1e-6);
    EXPECT_NEAR(glm::dot(f.t, n), 0.0, 1e-6);
    EXPECT_NEAR(glm::dot(f.b, n), 0.0, 1e-6);
    const vec3 c = glm::cross(f.t, f.b);  // right-handed: t x b = n
    EXPECT_NEAR(c.x, n.x, 1e-6);
    EXPECT_NEAR(c.y, n.y, 1e-6);
    EXPECT_NEAR(c.z, n.z, 1e-6);
}

TEST(Hemisphere, BasisIsOrthonormalForEveryNormal) {
    Kernel k;
    std::vector<vec3> normals;
    // The six axes with every combination of signed zeros in the other components.
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            for (int zeros = 0; zeros < 4; ++zeros) {
                vec3 n((zeros & 1) ? -0.0f : 0.0f, (zeros & 2) ? -0.0f : 0.0f, 0.0f);
                if (axis == 2) n = vec3(n.x, n.y, sign);
                if (axis == 0) n = vec3(sign, n.x, n.y);
                if (axis == 1) n = vec3(n.x, sign, n.y);
                normals.push_back(n);
            }
        }
    }
    // Near -z and +z, where the classic constructions divide by almost nothing.
    for (float e : {1e-3f, 1e-5f, 1e-7f, 1e-20f}) {
        normals.push_back(glm::normalize(vec3(e, 0.0f, -1.0f)));
        normals.push_back(glm::normalize(vec3(0.0f, -e, -1.0f)));
        normals.push_back(glm::normalize(vec3(e, e, 1.0f)));
    }
    std::mt19937 rng(1);
    std::normal_distribution<float> gauss;
    for (int i = 0; i < 10000; ++i) {
        const vec3 g(gauss(rng), gauss(rng), gauss(rng));
        if (glm::length(g) > 0.0f) normals.push_back(glm::normalize(g));
    }
    for (const vec3& n : normals) expect_orthonormal(k.basis_around(n), n);
}

// Monte Carlo over `count` draws: the mean of f(d) / pdf(d) and its standard error.
struct Estimate {
    double mean;
    double error;
};

template <class F>
Estimate estimate(Kernel& k, vkrt::kernel::uint kind, int count, F f) {
    std::mt19937 rng(7 + kind);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < count; ++i) {
        const vec3 d = k.sample_hemisphere(kind, unit(rng), unit(rng));
        EXPECT_NEAR(glm::length(d), 1.0, 1e-6);
        EXPECT_GT(d.z, 0.0f);
        const double v = f(d) / double(k.hemisphere_pdf(kind, d));
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / count;
    return {mean, std::sqrt(std::max(0.0, sum2 / count - mean * mean) / count)};
}

TEST(Hemisphere, EachSamplerMatchesItsDensity) {
    // With the right density, E[f / p] is the integral of f over the hemisphere:
    // 2 pi for f = 1, pi for f = cos(theta), 2 pi / 3 for f = cos^2(theta).
    Kernel k;
    const double pi = 3.14159265358979;
    for (auto kind : {vkrt::kernel::HEMISPHERE_ANGLES, vkrt::kernel::HEMISPHERE_UNIFORM, vkrt::kernel::HEMISPHERE_COSINE}) {
        SCOPED_TRACE(testing::Message() << "kind " << kind);
        const Estimate area = estimate(k, kind, 200000, [](vec3) { return 1.0; });
        // Four standard errors, plus float rounding of the density where f / p is
        // constant (uniform for f = 1, cosine for f = cos) and the variance is zero.
        EXPECT_NEAR(area.mean, 2.0 * pi, 4.0 * area.error + 1e-6 * 2.0 * pi);
        const Estimate cosine = estimate(k, kind, 200000, [](vec3 d) { return double(d.z); });
        EXPECT_NEAR(cosine.mean, pi, 4.0 * cosine.error + 1e-6 * pi);
        const Estimate cos2 = estimate(k, kind, 200000, [](vec3 d) { return double(d.z) * d.z; });
        EXPECT_NEAR(cos2.mean, 2.0 * pi / 3.0, 4.0 * cos2.error + 1e-6 * pi);
    }
}

TEST(Hemisphere, TheSamplersDistributeDifferently) {
    // The mean of cos(theta) under each: angles 2 / pi, uniform 1 / 2, cosine 2 / 3.
    Kernel k;
    const double pi = 3.14159265358979;
    const double want[] = {2.0 / pi, 0.5, 2.0 / 3.0};
    for (auto kind : {vkrt::kernel::HEMISPHERE_ANGLES, vkrt::kernel::HEMISPHERE_UNIFORM, vkrt::kernel::HEMISPHERE_COSINE}) {
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        double sum = 0.0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) sum += k.sample_hemisphere(kind, unit(rng), unit(rng)).z;
        EXPECT_NEAR(sum / n, want[kind], 0.004) << "kind " << kind;
    }
    // Cosine sampling at u1 = 0 is the normal itself; no sampler reaches the horizon.
    EXPECT_EQ(k.sample_hemisphere(vkrt::kernel::HEMISPHERE_COSINE, 0.0f, 0.0f).z, 1.0f);
    const float last = 1.0f - 0x1p-24f;  // the largest number rng_next returns
    for (auto kind : {vkrt::kernel::HEMISPHERE_ANGLES, vkrt::kernel::HEMISPHERE_UNIFORM, vkrt::kernel::HEMISPHERE_COSINE}) {
        EXPECT_GT(k.sample_hemisphere(kind, last, 0.5f).z, 0.0f) << "kind " << kind;
    }
    EXPECT_EQ(k.hemisphere_pdf(vkrt::kernel::HEMISPHERE_UNIFORM, vec3(0.0f, 0.0f, -1.0f)), 0.0f);
}

}  // namespace
