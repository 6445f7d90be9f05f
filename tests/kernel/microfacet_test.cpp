// The GGX lobe of the metallic-roughness material (shaders/kernel/lobes/ggx.glsl,
// bsdf.glsl) against the formulas written again here in double precision: the
// distribution's normalization, the sampled density against the evaluated one (a
// chi-square test over the sphere), the white furnace (a lobe of reflectance 1
// reflects what its single-scattering albedo, integrated here, says, and never
// more than 1), the albedo tables and the multiple-scattering lobe that gives back
// what single scattering loses (lobes/ggx_multiple.glsl), reciprocity and energy
// conservation of the diffuse + rough sum.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "flatten/ggx_albedo.hpp"
#include "flatten/sheen_albedo.hpp"
#include "ggx_reference.hpp"
#include "kernel/kernel.hpp"
#include "statistics.hpp"

namespace {

using vkrt::kernel::Kernel;
using vkrt::kernel::vec3;
using vkrt::kernel::vec4;

using vkrt::test::ggx::kPi;

// ---------------------------------------------------------- formulas in double

// f cos(theta_i) dw_i of a lobe with F = 1, for wo at cos_o in the xz plane, per unit
// solid angle of the half vector h = (hx, hy, hz): D G2 (wo.h) / cos_o, where
// dw_i = 4 (wo.h) dw_h; 0 where the reflected direction lies below the surface.
double lobe_cos_per_h(double alpha, double cos_o, double hx, double hy, double hz) {
    const double ox = std::sqrt(1.0 - cos_o * cos_o), oz = cos_o;
    const double oh = ox * hx + oz * hz;
    if (!(oh > 0.0)) return 0.0;
    const double iz = 2.0 * oh * hz - oz;
    if (!(iz > 0.0)) return 0.0;
    (void)hy;
    return vkrt::test::ggx::d(hz, alpha) * vkrt::test::ggx::g2(cos_o, iz, alpha) * oh / cos_o;
}

// The same per unit solid angle of wi = (ix, iy, iz), for comparing values.
double lobe_cos(double alpha, double cos_o, double ix, double iy, double iz) {
    if (!(iz > 0.0)) return 0.0;
    const double ox = std::sqrt(1.0 - cos_o * cos_o), oz = cos_o;
    const double hx = ox + ix, hy = iy, hz = oz + iz;
    const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
    return vkrt::test::ggx::d(hz / len, alpha) * vkrt::test::ggx::g2(cos_o, iz, alpha) / (4.0 * cos_o);
}

// The hemisphere integral of fn(x, y, z) by the midpoint rule in (cos theta, phi),
// with cos theta refined toward the pole where narrow lobes live: cos theta = 1 - s^4.
template <class Fn>
double hemisphere_integral(Fn fn, int n_theta = 800, int n_phi = 800) {
    double sum = 0.0;
    for (int i = 0; i < n_theta; ++i) {
        const double s = (i + 0.5) / n_theta;
        const double z = 1.0 - s * s * s * s;
        const double dz = 4.0 * s * s * s / n_theta;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        for (int j = 0; j < n_phi; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / n_phi;
            sum += fn(r * std::cos(phi), r * std::sin(phi), z) * dz * (2.0 * kPi / n_phi);
        }
    }
    return sum;
}

// The single-scattering directional albedo of a lobe of reflectance 1, integrated over
// the half vector, whose density peaks at the normal for every wo.
double albedo(double alpha, double cos_o) {
    return hemisphere_integral([&](double x, double y, double z) { return lobe_cos_per_h(alpha, cos_o, x, y, z); });
}

vec3 from_cos(double c) { return vec3(float(std::sqrt(1.0 - c * c)), 0.0f, float(c)); }

// The integral of fn(wi) over the hemisphere, taken over the half vector h of wo and
// wi (dw_i = 4 (wo.h) dw_h), where narrow reflection lobes are all near the pole.
template <class Fn>
double reflected_integral(vec3 wo, Fn fn) {
    return hemisphere_integral(
        [&](double hx, double hy, double hz) {
            const double oh = wo.x * hx + wo.y * hy + wo.z * hz;
            const vec3 wi(float(2.0 * oh * hx - wo.x), float(2.0 * oh * hy - wo.y), float(2.0 * oh * hz - wo.z));
            if (!(oh > 0.0 && wi.z > 0.0f)) return 0.0;
            return fn(glm::normalize(wi)) * 4.0 * oh;
        },
        400, 400);
}

const vec3 kUp(0.0f, 0.0f, 1.0f);

// A kernel that reads the rough lobe's albedo tables, as a flattened scene with a
// metallic-roughness material gives them.
Kernel kernel_with_tables() {
    Kernel k;
    k.table_words = vkrt::ggx_albedo_table();
    vkrt::kernel::set_ggx_table_first_word(k.params, 0u);
    return k;
}

// ---------------------------------------------------------------------- tests

TEST(Ggx, DistributionOfNormalsProjectsToOne) {
    Kernel k;
    for (double alpha : {0.01, 0.05, 0.2, 0.5, 1.0}) {
        const double projected = hemisphere_integral(
            [&](double, double, double z) { return double(k.ggx_d(float(z), float(alpha))) * z; }, 4000, 4);
        EXPECT_NEAR(projected, 1.0, 1e-3) << "alpha " << alpha;
    }
}

TEST(Ggx, EvaluationMatchesTheFormulaInDouble) {
    Kernel k;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.02, 1.0), phi(0.0, 2.0 * kPi);
    for (double alpha : {0.001, 0.05, 0.3, 1.0}) {
        for (int i = 0; i < 200; ++i) {
            const double co = u(rng), ci = u(rng), p = phi(rng);
            const double si = std::sqrt(1.0 - ci * ci);
            const vec3 wi(float(si * std::cos(p)), float(si * std::sin(p)), float(ci));
            const vec3 wo = from_cos(co);
            // With reflectance 1, F is 1 at every angle.
            const double f = k.ggx_eval(vec3(1.0f), 1.0f, float(alpha), kUp, wo, wi).x;
            const double expected = lobe_cos(alpha, co, wi.x, wi.y, wi.z) / wi.z;
            EXPECT_NEAR(f, expected, 2e-4 * expected + 1e-6) << "alpha " << alpha << " cos_o " << co << " cos_i " << ci;
        }
    }
}

TEST(Ggx, SchlickFresnelRunsFromF0ToOne) {
    Kernel k;
    EXPECT_EQ(k.fresnel_schlick(vec3(0.04f), 1.0f), vec3(0.04f));
    EXPECT_EQ(k.fresnel_schlick(vec3(0.04f), 0.0f), vec3(1.0f));
    EXPECT_NEAR(k.fresnel_schlick(vec3(0.04f), 0.5f).x, 0.04 + 0.96 / 32.0, 1e-7);
}

// The visible-normal sampler draws directions with the density ggx_pdf states: sample
// counts in 16 x 32 cells of the hemisphere (cos theta by phi) against the density
// integrated over each, and the share that falls below the surface against 1 less
// the density's integral over the hemisphere.
TEST(Ggx, SampledDirectionsFollowTheStatedDensity) {
    Kernel k;
    constexpr int kTheta = 16, kPhi = 32, kSamples = 400000;
    const std::vector<double> alphas{0.1, 0.3, 0.6, 1.0}, cosines{0.95, 0.5, 0.1};
    // Far into the tail, five standard deviations above the mean at the 400 to 500
    // degrees of freedom each case has: a fair sampler lands there in about one of
    // 400,000 runs of a case, one of 33,000 runs of all twelve.
    const double level = vkrt::test::sidak_significance(3e-5, alphas.size() * cosines.size());
    for (double alpha : alphas) {
        for (double co : cosines) {
            SCOPED_TRACE(testing::Message() << "alpha " << alpha << " cos_o " << co);
            const vec3 wo = from_cos(co);
            std::vector<double> count(kTheta * kPhi, 0.0);
            double below = 0.0;
            std::mt19937 rng(11);
            std::uniform_real_distribution<float> u(0.0f, 1.0f);
            for (int i = 0; i < kSamples; ++i) {
                const vec3 wi = k.ggx_sample(float(alpha), wo, u(rng), u(rng));
                ASSERT_NEAR(glm::length(wi), 1.0f, 1e-5f);
                if (!(wi.z > 0.0f)) {
                    below += 1.0;
                    continue;
                }
                const int t = std::min(kTheta - 1, int((1.0f - wi.z) * kTheta));
                double p = std::atan2(double(wi.y), double(wi.x));
                if (p < 0.0) p += 2.0 * kPi;
                const int f = std::min(kPhi - 1, int(p / (2.0 * kPi) * kPhi));
                count[t * kPhi + f] += 1.0;
            }
            std::vector<double> expected(kTheta * kPhi);
            double mass = 0.0;
            for (int t = 0; t < kTheta; ++t) {
                for (int f = 0; f < kPhi; ++f) {
                    double integral = 0.0;
                    constexpr int q = 24;  // midpoint rule within the cell
                    for (int a = 0; a < q; ++a) {
                        for (int b = 0; b < q; ++b) {
                            const double z = 1.0 - (t + (a + 0.5) / q) / kTheta;
                            const double p = 2.0 * kPi * (f + (b + 0.5) / q) / kPhi;
                            const double r = std::sqrt(1.0 - z * z);
                            const vec3 wi(float(r * std::cos(p)), float(r * std::sin(p)), float(z));
                            integral += k.ggx_pdf(float(alpha), kUp, wo, wi);
                        }
                    }
                    integral *= (1.0 / kTheta) * (2.0 * kPi / kPhi) / (q * q);
                    mass += integral;
                    expected[t * kPhi + f] = integral * kSamples;
                }
            }
            // The draws below the surface are in no cell; cells expecting fewer than
            // 20 are pooled.
            const vkrt::test::ChiSquareResult fit =
                vkrt::test::chi_square_test(count, expected, {.min_expected = 20.0, .bins_hold_every_draw = false});
            ASSERT_GT(fit.degrees_of_freedom, 20);
            EXPECT_GT(fit.p_value, level) << fit;
            EXPECT_NEAR(below / kSamples, 1.0 - mass, 4e-3);
        }
    }
}

// A white lobe (F = 1) reflects its single-scattering albedo, computed here from the
// formulas: the estimate from the kernel's own samples and weights agrees with it,
// no albedo exceeds 1, and the energy lost to multiple scattering between
// microfacets grows with roughness as it should (near 0 when smooth).
TEST(Ggx, WhiteFurnaceLosesOnlyTheMultipleScattering) {
    Kernel k;
    std::printf("alpha  cos_o  albedo (quadrature)  albedo (kernel samples)\n");
    for (double alpha : {0.01, 0.1, 0.3, 0.6, 1.0}) {
        for (double co : {1.0, 0.7, 0.3, 0.1}) {
            SCOPED_TRACE(testing::Message() << "alpha " << alpha << " cos_o " << co);
            const double expected = albedo(alpha, co);
            const vec3 wo = from_cos(co);
            std::mt19937 rng(5);
            std::uniform_real_distribution<float> u(0.0f, 1.0f);
            constexpr int n = 200000;
            double sum = 0.0, sum2 = 0.0;
            for (int i = 0; i < n; ++i) {
                const vec3 wi = k.ggx_sample(float(alpha), wo, u(rng), u(rng));
                const float pdf = k.ggx_pdf(float(alpha), kUp, wo, wi);
                const double w = pdf > 0.0f ? k.ggx_eval(vec3(1.0f), 1.0f, float(alpha), kUp, wo, wi).x * wi.z / pdf : 0.0;
                ASSERT_LE(w, 1.0 + 1e-4) << "a visible-normal sample's weight is G2 / G1 <= 1";
                sum += w;
                sum2 += w * w;
            }
            const double mean = sum / n;
            const double error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
            std::printf("%5.2f  %5.2f  %.5f  %.5f\n", alpha, co, expected, mean);
            EXPECT_LE(expected, 1.0 + 1e-4);
            EXPECT_NEAR(mean, expected, 4.0 * error + 2e-4);
            if (alpha <= 0.01) {
                EXPECT_GT(expected, 0.99);
            }
        }
    }
    // The loss grows with roughness.
    for (double alpha : {0.01, 0.1, 0.3, 0.6}) EXPECT_GT(albedo(alpha, 1.0), albedo(2.0 * alpha, 1.0));
    // The hemispherical average 2 int E(mu) mu dmu of the roughest lobe, alpha = 1:
    // single scattering loses about 60% of the light there (Turquin, "Practical
    // multiple scattering compensation for microfacet models", 2019, Fig. 2).
    double average = 0.0;
    constexpr int n_mu = 32;
    for (int i = 0; i < n_mu; ++i) {
        const double mu = (i + 0.5) / n_mu;
        average += 2.0 * albedo(1.0, mu) * mu / n_mu;
    }
    std::printf("hemispherical average albedo at alpha 1: %.4f\n", average);
    EXPECT_NEAR(average, 0.4, 0.05);
}

// An untextured metallic-roughness material as flat_scene.cpp builds it.
vkrt::kernel::Material metallic_roughness(vec3 base_color, float metallic, float roughness) {
    vkrt::kernel::Material m{};
    m.diffuse = (1.0f - metallic) * base_color;
    m.kd = 1.0f;
    m.ior = 1.5f;
    m.ggx_f0 = glm::mix(vec3(0.04f), base_color, metallic);
    m.ggx_f90 = 1.0f;
    m.ggx_alpha = roughness * roughness;
    return m;
}

// Its lobes as bsdf.glsl assembles them.
Kernel::Lobes lobes_of(Kernel& k, vec3 base_color, float metallic, float roughness, float cos_o) {
    return k.material_lobes(metallic_roughness(base_color, metallic, roughness), kUp, kUp, from_cos(cos_o));
}

TEST(MetallicRoughness, IsReciprocal) {
    Kernel k = kernel_with_tables();
    std::mt19937 rng(9);
    std::normal_distribution<float> g;
    for (int i = 0; i < 500; ++i) {
        vec3 a(g(rng), g(rng), std::abs(g(rng)) + 0.01f), b(g(rng), g(rng), std::abs(g(rng)) + 0.01f);
        a = glm::normalize(a);
        b = glm::normalize(b);
        const Kernel::Lobes l = lobes_of(k, vec3(0.8f, 0.5f, 0.2f), 0.3f, 0.4f, a.z);
        const vec3 ab = k.eval_smooth(l, kUp, a, b), ba = k.eval_smooth(l, kUp, b, a);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ab[c], ba[c], 1e-5f * std::max(1.0f, ab[c]));
    }
}

// The sum of the diffuse and rough lobes of a white dielectric and of a white metal
// reflects at most all the light, and nearly all of it, from every direction, by
// quadrature of the kernel's own evaluation: the metal by its single and multiple
// scattering together, the dielectric by the diffuse lobe that takes what the
// rough lobe leaves.
TEST(MetallicRoughness, ConservesEnergy) {
    Kernel k = kernel_with_tables();
    for (float metallic : {0.0f, 1.0f}) {
        for (float roughness : {0.2f, 0.5f, 1.0f}) {
            for (double co : {1.0, 0.5, 0.1}) {
                const vec3 wo = from_cos(co);
                const Kernel::Lobes l = lobes_of(k, vec3(1.0f), metallic, roughness, float(co));
                const double reflected =
                    reflected_integral(wo, [&](vec3 wi) { return double(k.eval_smooth(l, kUp, wo, wi).x) * wi.z; });
                std::printf("metallic %.0f roughness %.1f cos_o %.1f: %.4f\n", metallic, roughness, co, reflected);
                SCOPED_TRACE(testing::Message() << "metallic " << metallic << " roughness " << roughness << " cos_o " << co);
                EXPECT_LE(reflected, 1.0 + 2e-3);
                // White under a rough coat, or a white metal: nearly all.
                EXPECT_GE(reflected, metallic == 1.0f ? 0.98 : 0.95);
            }
        }
    }
}

// The mixture's stated density integrates to what lands above the surface, and
// sample_smooth follows it: the kernel's weight eval cos / pdf averages to the
// quadrature of eval cos.
// The mixture l, seen from cos(theta_o) = co, draws by the density it states: the
// kernel's weight eval cos / pdf over 200,000 draws (seed `seed`) averages to the
// quadrature of eval cos, in the green channel, within four standard errors.
void expect_sampling_follows_density(Kernel& k, const Kernel::Lobes& l, double co, unsigned seed) {
    const Kernel::Basis frame = k.basis_around(kUp);
    const vec3 wo = from_cos(co);
    const double expected = reflected_integral(wo, [&](vec3 wi) { return double(k.eval_smooth(l, kUp, wo, wi).y) * wi.z; });
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    constexpr int n = 200000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const vec3 wi = k.sample_smooth(l, frame, wo, vkrt::kernel::HEMISPHERE_COSINE, u(rng), u(rng), u(rng));
        const float pdf = k.pdf_smooth(l, frame, wo, wi, vkrt::kernel::HEMISPHERE_COSINE);
        const double w = wi.z > 0.0f && pdf > 0.0f ? k.eval_smooth(l, kUp, wo, wi).y * wi.z / pdf : 0.0;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    const double error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4.0 * error + 2e-4);
}

TEST(MetallicRoughness, MixtureSamplingMatchesItsDensity) {
    Kernel k = kernel_with_tables();
    for (float metallic : {0.0f, 0.5f}) {
        for (double co : {0.9, 0.3}) {
            SCOPED_TRACE(testing::Message() << "metallic " << metallic << " cos_o " << co);
            expect_sampling_follows_density(k, lobes_of(k, vec3(0.9f, 0.6f, 0.3f), metallic, 0.5f, float(co)), co, 21);
        }
    }
}


// The tables hold the single-scattering albedo the quadrature above gives, at their
// knots: mu = (i / 31)^2, r = j / 31, alpha = r^2 (at least MIN_GGX_ALPHA).
TEST(GgxTables, HoldTheAlbedoAtTheirKnots) {
    const std::vector<std::uint32_t>& table = vkrt::ggx_albedo_table();
    constexpr int n = int(vkrt::kernel::GGX_TABLE_SIZE);
    ASSERT_EQ(table.size(), std::size_t(2 * (n * n + n)));  // E, then E_s
    for (int j : {1, 6, 15, 31}) {
        for (int i : {3, 10, 22, 31}) {
            const double r = double(j) / (n - 1), mu = double(i * i) / ((n - 1) * (n - 1));
            const double alpha = std::max(r * r, double(vkrt::kernel::MIN_GGX_ALPHA));
            SCOPED_TRACE(testing::Message() << "alpha " << alpha << " mu " << mu);
            EXPECT_NEAR(std::bit_cast<float>(table[std::size_t(j * n + i)]), albedo(alpha, mu), 3e-3);
        }
    }
}

// A white metal (F = 1) keeps the light at every roughness and angle once the
// multiple-scattering lobe gives back what single scattering loses: quadrature of
// the kernel's own rough lobes, the single-scattering one alone and both. The table
// printed is decision 0040's.
TEST(GgxMultiple, WhiteFurnaceKeepsTheLight) {
    Kernel k = kernel_with_tables();
    vkrt::kernel::Material m{};
    m.ggx_f0 = vec3(1.0f);
    m.ggx_f90 = 1.0f;
    std::printf("roughness  cos_o  single  single + multiple\n");
    for (float roughness : {0.1f, 0.3f, 0.5f, 0.7f, 0.85f, 1.0f}) {
        m.ggx_alpha = std::max(roughness * roughness, vkrt::kernel::MIN_GGX_ALPHA);
        for (double co : {1.0, 0.7, 0.4, 0.2, 0.05}) {
            SCOPED_TRACE(testing::Message() << "roughness " << roughness << " cos_o " << co);
            const vec3 wo = from_cos(co);
            const Kernel::Lobes l = k.material_lobes(m, kUp, kUp, from_cos(float(co)));
            const double single =
                reflected_integral(wo, [&](vec3 wi) { return double(k.ggx_eval(l.ggx, kUp, wo, wi).x) * wi.z; });
            const double multiple = hemisphere_integral(
                [&](double x, double y, double z) {
                    return double(k.ggx_multiple_eval(l.ggx_multiple, kUp, wo, vec3(float(x), float(y), float(z))).x) * z;
                },
                200, 50);
            std::printf("%9.2f  %5.2f  %.4f  %.4f\n", roughness, co, single, single + multiple);
            EXPECT_GE(single + multiple, 0.98);
            EXPECT_LE(single + multiple, 1.0 + 2e-3);
            // Its weight is what it reflects from wo, the share sampling gives it.
            EXPECT_NEAR(l.ggx_multiple.weight, multiple, 2e-3);
        }
    }
}

// Reciprocal, and drawn by the cosine-weighted density it states.
TEST(GgxMultiple, IsReciprocalAndFollowsItsDensity) {
    Kernel k = kernel_with_tables();
    vkrt::kernel::Material m{};
    m.ggx_f0 = vec3(0.9f, 0.6f, 0.3f);
    m.ggx_f90 = 1.0f;
    m.ggx_alpha = 0.64f;
    std::mt19937 rng(3);
    std::normal_distribution<float> g;
    for (int i = 0; i < 200; ++i) {
        vec3 a = glm::normalize(vec3(g(rng), g(rng), std::abs(g(rng)) + 0.01f));
        vec3 b = glm::normalize(vec3(g(rng), g(rng), std::abs(g(rng)) + 0.01f));
        const vec3 ab = k.ggx_multiple_eval(k.material_lobes(m, kUp, kUp, from_cos(a.z)).ggx_multiple, kUp, a, b);
        const vec3 ba = k.ggx_multiple_eval(k.material_lobes(m, kUp, kUp, from_cos(b.z)).ggx_multiple, kUp, b, a);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ab[c], ba[c], 1e-5f * std::max(1.0f, ab[c]));
    }
    const Kernel::Basis frame = k.basis_around(kUp);
    const vec3 wo = from_cos(0.5);
    const Kernel::GgxMultipleLobe l = k.material_lobes(m, kUp, kUp, from_cos(0.5f)).ggx_multiple;
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        const vec3 wi = k.ggx_multiple_sample(l, frame, wo, vkrt::kernel::HEMISPHERE_UNIFORM, u(rng), u(rng));
        ASSERT_GT(wi.z, 0.0f);
        EXPECT_NEAR(k.ggx_multiple_pdf(l, frame, wo, wi, vkrt::kernel::HEMISPHERE_UNIFORM), wi.z / kPi, 1e-5);
    }
}

// ------------------------------------------------------------ the clear coat

// The metallic-roughness material of lobes_of under a clear coat of factor `coat` and
// roughness `coat_roughness` (lobes/coat.glsl).
Kernel::Lobes coated_lobes_of(Kernel& k, vec3 base_color, float metallic, float roughness, float coat,
                              float coat_roughness, float cos_o) {
    vkrt::kernel::Material m = metallic_roughness(base_color, metallic, roughness);
    m.coat = coat;
    m.coat_alpha = coat_roughness * coat_roughness;
    return k.material_lobes(m, kUp, kUp, from_cos(cos_o));
}

// Under a coat, a white base keeps reflecting all it did: by quadrature of the
// kernel's own evaluation, at most all the light and at least what the base alone
// reflects less 0.5% (the coat's own multiple scattering is not followed). Over a
// black dielectric the sum is the layering's closed form, c R_coat + (1 - c R_coat)
// R_base, with each albedo from the tables (which GgxTables checks against
// quadrature).
TEST(Coat, KeepsAWhiteBasesLightAndLayersByItsAlbedo) {
    Kernel k = kernel_with_tables();
    for (float metallic : {0.0f, 1.0f}) {
        for (float coat_roughness : {0.1f, 0.5f, 1.0f}) {
            for (double co : {1.0, 0.5, 0.1}) {
                SCOPED_TRACE(testing::Message() << "metallic " << metallic << " coat roughness " << coat_roughness
                                                << " cos_o " << co);
                const vec3 wo = from_cos(co);
                const auto reflected = [&](const Kernel::Lobes& l) {
                    return reflected_integral(wo, [&](vec3 wi) { return double(k.eval_smooth(l, kUp, wo, wi).x) * wi.z; });
                };
                const double bare = reflected(lobes_of(k, vec3(1.0f), metallic, 0.5f, float(co)));
                const double coated = reflected(coated_lobes_of(k, vec3(1.0f), metallic, 0.5f, 1.0f, coat_roughness, float(co)));
                std::printf("white, metallic %.0f, coat roughness %.1f, cos_o %.1f: %.4f bare, %.4f coated\n", metallic,
                            coat_roughness, co, bare, coated);
                EXPECT_LE(coated, 1.0 + 2e-3);
                EXPECT_GE(coated, bare - 5e-3);

                const float alpha = coat_roughness * coat_roughness;
                const double r_coat = 0.04 * k.ggx_albedo(float(co), alpha) +
                                      0.96 * k.ggx_table_lookup(k.GGX_SCHLICK_TABLE, float(co), alpha);
                const double r_base = k.ggx_reflectance(vec3(0.04f), 1.0f, float(co), 0.25f).x;
                const double black = reflected(coated_lobes_of(k, vec3(0.0f), 0.0f, 0.5f, 0.5f, coat_roughness, float(co)));
                EXPECT_NEAR(black, 0.5 * r_coat + (1.0 - 0.5 * r_coat) * r_base, 2e-3);
            }
        }
    }
}

// The coat joins the smooth group's mixture: sampling follows the stated density,
// and the coat's weight over glass brings the group back when the rest is all glass.
TEST(Coat, MixtureSamplingMatchesItsDensity) {
    Kernel k = kernel_with_tables();
    for (double co : {0.9, 0.3}) {
        SCOPED_TRACE(testing::Message() << "cos_o " << co);
        const Kernel::Lobes l = coated_lobes_of(k, vec3(0.9f, 0.6f, 0.3f), 0.0f, 0.7f, 0.8f, 0.2f, float(co));
        EXPECT_GT(l.coat.weight, 0.0f);
        EXPECT_LT(l.under_coat, 1.0f);
        expect_sampling_follows_density(k, l, co, 5);
    }
    vkrt::kernel::Material glass{};
    glass.ggx_f0 = vec3(0.04f);
    glass.ggx_f90 = 1.0f;
    glass.ggx_alpha = 0.25f;
    glass.transmission = 1.0f;
    glass.transmit = vec3(1.0f);
    glass.coat = 1.0f;
    glass.coat_alpha = 0.01f;
    const Kernel::Lobes l = k.material_lobes(glass, kUp, kUp, from_cos(0.8f));
    EXPECT_EQ(l.smooth_share, 0.0f);
    EXPECT_FLOAT_EQ(k.smooth_weight(l), l.coat.weight);
    EXPECT_FLOAT_EQ(l.glass.weight, l.under_coat);
}

// ------------------------------------------------------------------ sheen

// A kernel that reads the rough lobe's tables and the sheen's after them, as a
// flattened scene with sheen gives them.
Kernel kernel_with_sheen_table() {
    static const std::vector<std::uint32_t> words = [] {
        std::vector<std::uint32_t> w = vkrt::ggx_albedo_table();
        const std::vector<std::uint32_t>& sheen = vkrt::sheen_albedo_table();
        w.insert(w.end(), sheen.begin(), sheen.end());
        return w;
    }();
    Kernel k;
    k.table_words = words;
    vkrt::kernel::set_ggx_table_first_word(k.params, 0u);
    return k;
}

// lobes_of's material with sheen of colour `sheen` and roughness `sheen_roughness`,
// and a coat of factor `coat` (roughness 0.3).
Kernel::Lobes sheened_lobes_of(Kernel& k, vec3 base_color, float metallic, vec3 sheen, float sheen_roughness,
                               float coat, float cos_o) {
    vkrt::kernel::Material m = metallic_roughness(base_color, metallic, 0.5f);
    m.sheen_color = sheen;
    m.sheen_alpha = std::max(sheen_roughness * sheen_roughness, vkrt::kernel::MIN_SHEEN_ALPHA);
    m.coat = coat;
    m.coat_alpha = 0.09f;
    return k.material_lobes(m, kUp, kUp, from_cos(cos_o));
}

// The table holds the sheen's albedo that quadrature of the kernel's own sheen_value
// gives, at knots and between them.
TEST(Sheen, TableHoldsTheAlbedo) {
    Kernel k = kernel_with_sheen_table();
    for (float roughness : {0.0f, 0.3f, 0.45f, 0.6f, 1.0f}) {
        for (double co : {1.0, 0.7, 0.3, 0.1, 0.03}) {
            const float alpha = std::max(roughness * roughness, vkrt::kernel::MIN_SHEEN_ALPHA);
            const vec3 wo = from_cos(co);
            const double e = reflected_integral(wo, [&](vec3 wi) { return double(k.sheen_value(alpha, kUp, wo, wi)) * wi.z; });
            const double table = k.ggx_table_lookup(k.SHEEN_TABLE, float(co), alpha);
            std::printf("sheen roughness %.2f cos_o %.1f: quadrature %.4f, table %.4f\n", roughness, co, e, table);
            EXPECT_NEAR(table, e, 0.005 * e + 1e-3) << "roughness " << roughness << " cos_o " << co;
        }
    }
}

// Under a white sheen a white base keeps reflecting all the light and no more, and
// under sheen and a coat together; over a black dielectric the sum is the layering's
// closed form: E_sheen + (1 - E_sheen) R_base, with each albedo from the tables.
TEST(Sheen, KeepsAWhiteBasesLightAndLayersByItsAlbedo) {
    Kernel k = kernel_with_sheen_table();
    for (float roughness : {0.0f, 0.5f, 1.0f}) {
        for (double co : {1.0, 0.5, 0.1}) {
            SCOPED_TRACE(testing::Message() << "sheen roughness " << roughness << " cos_o " << co);
            const vec3 wo = from_cos(co);
            const auto reflected = [&](const Kernel::Lobes& l) {
                return reflected_integral(wo, [&](vec3 wi) { return double(k.eval_smooth(l, kUp, wo, wi).x) * wi.z; });
            };
            for (float coat : {0.0f, 1.0f}) {
                const double white = reflected(sheened_lobes_of(k, vec3(1.0f), 0.0f, vec3(1.0f), roughness, coat, float(co)));
                std::printf("white under sheen %.2f, coat %.0f, cos_o %.1f: %.4f\n", roughness, coat, co, white);
                EXPECT_LE(white, 1.0 + 2e-3);
                EXPECT_GE(white, 0.99);
            }
            const Kernel::Lobes black = sheened_lobes_of(k, vec3(0.0f), 0.0f, vec3(0.5f), roughness, 0.0f, float(co));
            const double e = k.ggx_table_lookup(k.SHEEN_TABLE, float(co), black.sheen.alpha);
            const double r_base = k.ggx_reflectance(vec3(0.04f), 1.0f, float(co), 0.25f).x;
            EXPECT_NEAR(reflected(black), 0.5 * e + (1.0 - 0.5 * e) * r_base, 2e-3);
        }
    }
}

TEST(Sheen, MixtureSamplingMatchesItsDensity) {
    Kernel k = kernel_with_sheen_table();
    for (double co : {0.9, 0.2}) {
        SCOPED_TRACE(testing::Message() << "cos_o " << co);
        const Kernel::Lobes l = sheened_lobes_of(k, vec3(0.2f, 0.3f, 0.6f), 0.0f, vec3(0.9f, 0.8f, 0.7f), 0.4f, 0.5f, float(co));
        EXPECT_GT(l.sheen.weight, 0.0f);
        EXPECT_LT(l.sheen.keep, 1.0f);
        expect_sampling_follows_density(k, l, co, 8);
    }
}

// ------------------------------------------------------- the dielectric's specular layer

// lobes_of's dielectric with glTF's KHR_materials_specular, as flat_scene.cpp builds it:
// f0 = min(0.04 colour, 1) specular, f90 = specular.
Kernel::Lobes specular_lobes_of(Kernel& k, vec3 base_color, float roughness, float specular, vec3 color, float cos_o) {
    vkrt::kernel::Material m = metallic_roughness(base_color, 0.0f, roughness);
    m.ggx_f0 = glm::min(0.04f * color, vec3(1.0f)) * specular;
    m.ggx_f90 = specular;
    return k.material_lobes(m, kUp, kUp, from_cos(cos_o));
}

// Schlick's Fresnel runs from f0 to f90.
TEST(DielectricSpecular, FresnelRunsFromF0ToF90) {
    Kernel k;
    EXPECT_EQ(k.fresnel_schlick(vec3(0.02f), 0.5f, 1.0f), vec3(0.02f));
    EXPECT_EQ(k.fresnel_schlick(vec3(0.02f), 0.5f, 0.0f), vec3(0.5f));
    EXPECT_NEAR(k.fresnel_schlick(vec3(0.02f), 0.5f, 0.5f).x, 0.02 + 0.48 / 32.0, 1e-7);
}

// Whatever the specular layer's strength and colour, a white base keeps reflecting
// all the light, by quadrature of the kernel's own evaluation, the diffuse lobe taking
// what the layer leaves; over a black base the layer reflects what the tables say,
// f0 E + (f90 - f0) E_s + F_ms (1 - E) (ggx_albedo.glsl); with a strength of 0 the
// material is Lambertian: the rough lobe weighs nothing.
TEST(DielectricSpecular, KeepsAWhiteBasesLightAndReflectsByItsTables) {
    Kernel k = kernel_with_tables();
    for (float specular : {0.0f, 0.5f, 1.0f}) {
        for (vec3 color : {vec3(1.0f), vec3(8.0f, 1.0f, 0.25f)}) {
            for (float roughness : {0.2f, 0.6f, 1.0f}) {
                for (double co : {1.0, 0.5, 0.1}) {
                    SCOPED_TRACE(testing::Message() << "specular " << specular << " colour " << color.x << " roughness "
                                                    << roughness << " cos_o " << co);
                    const vec3 wo = from_cos(co);
                    const auto reflected = [&](const Kernel::Lobes& l, int c) {
                        return reflected_integral(wo, [&](vec3 wi) { return double(k.eval_smooth(l, kUp, wo, wi)[c]) * wi.z; });
                    };
                    const Kernel::Lobes white = specular_lobes_of(k, vec3(1.0f), roughness, specular, color, float(co));
                    const Kernel::Lobes black = specular_lobes_of(k, vec3(0.0f), roughness, specular, color, float(co));
                    if (specular == 0.0f) {
                        EXPECT_EQ(white.ggx.weight, 0.0f);
                    }
                    const vec3 tables = k.ggx_reflectance(black.ggx.f0, black.ggx.f90, float(co), roughness * roughness);
                    for (int c = 0; c < 3; ++c) {
                        const double w = reflected(white, c);
                        EXPECT_LE(w, 1.0 + 2e-3) << "channel " << c;
                        EXPECT_GE(w, 0.99) << "channel " << c;
                        EXPECT_NEAR(reflected(black, c), tables[c], 2e-3) << "channel " << c;
                    }
                }
            }
        }
    }
}

TEST(DielectricSpecular, MixtureSamplingMatchesItsDensity) {
    Kernel k = kernel_with_tables();
    for (double co : {0.9, 0.2}) {
        SCOPED_TRACE(testing::Message() << "cos_o " << co);
        expect_sampling_follows_density(
            k, specular_lobes_of(k, vec3(0.3f, 0.5f, 0.7f), 0.4f, 0.6f, vec3(2.0f, 1.0f, 0.5f), float(co)), co, 9);
    }
}

}  // namespace
