// The numerical-stability suite (docs/numerics.md), case 7: refraction at and around the critical angle (energy conserved),
// an interface of ior 1, nested glass of equal ior (one body), rays trapped in a slab
// by total internal reflection (the tree and the bounce loops end); and case 10's
// hemisphere basis for axis and signed-zero normals, rendered on both backends.
// The scenes are in tests/scenes/stability/ (case7_*, case10_*).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "kernel/kernel.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::Kernel;
using kernel::vec3;

Scene stability_scene(const std::string& name) {
    return load_scene(test::source_dir() / "tests" / "scenes" / "stability" / name);
}

// The fraction of pixels whose channels all agree within `tolerance`.
double agreeing(const Image& a, const Image& b, float tolerance) {
    std::size_t same = 0;
    const std::size_t n = std::size_t(a.width) * a.height;
    for (std::size_t p = 0; p < n; ++p) {
        bool close = true;
        for (int c = 0; c < 3; ++c) close = close && std::abs(a.rgb[3 * p + c] - b.rgb[3 * p + c]) <= tolerance;
        same += close ? 1 : 0;
    }
    return double(same) / double(n);
}

// ------------------------------------------------ case 7: the Fresnel equations

// Reflected and transmitted power at an interface of relative index eta = n_i / n_t
// for unpolarized light, in double. T comes from the transmission amplitudes and the
// ratio of the beams' cross-sections, cos_t / (eta cos_i): not from 1 - R, so R + T = 1
// is a property of the optics here, and |R_kernel + T - 1| measures the kernel.
struct Power {
    double r = 1.0;
    double t = 0.0;
    bool total = true;
    double cos_t = 0.0;
};

Power fresnel_power(double cos_i, double eta) {
    // 1 - eta^2 (1 - cos_i^2) in a form that keeps cos_i at grazing incidence.
    const double cos2_t = (1.0 - eta) * (1.0 + eta) + eta * eta * cos_i * cos_i;
    if (!(cos2_t > 0.0)) return {};
    const double cos_t = std::sqrt(cos2_t);
    const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double ts = 2.0 * eta * cos_i / (eta * cos_i + cos_t);
    const double tp = 2.0 * eta * cos_i / (cos_i + eta * cos_t);
    const double beam = cos_i > 0.0 ? cos_t / (eta * cos_i) : 0.0;
    return {0.5 * (rs * rs + rp * rp), 0.5 * beam * (ts * ts + tp * tp), false, cos_t};
}

// Incidence angles from 0 to 90 degrees every 0.01 degree, plus, for eta > 1, the
// critical angle and 10^-k radians on either side of it, and grazing angles.
std::vector<double> incidence_angles(double eta) {
    const double pi = 3.14159265358979323846;
    std::vector<double> angles;
    for (int i = 0; i <= 9000; ++i) angles.push_back(i * pi / 18000.0);
    for (int k = 1; k <= 8; ++k) angles.push_back(pi / 2 - std::pow(10.0, -k));
    if (eta > 1.0) {
        const double critical = std::asin(1.0 / eta);
        angles.push_back(critical);
        for (int k = 1; k <= 8; ++k) {
            angles.push_back(critical - std::pow(10.0, -k));
            if (critical + std::pow(10.0, -k) <= pi / 2) angles.push_back(critical + std::pow(10.0, -k));
        }
    }
    return angles;
}

// The interface every glass hit meets: from air into glass of index `ior`, and out
// of it, as interface_eta computes them.
struct Interface {
    float ior;
    bool entering;
};

TEST(Refraction, ReflectedAndTransmittedPowerSumToOneAcrossTheCriticalAngle) {
    Kernel k;
    double worst_far = 0.0, worst_near = 0.0, worst_scaled = 0.0, worst_weights = 0.0, worst_snell = 0.0;
    int totals = 0, samples = 0;
    for (float ior : {1.0f, 1.0001f, 1.33f, 1.5f, 2.4f, 4.0f}) {
        for (bool entering : {true, false}) {
            const float eta = k.interface_eta(glm::uvec4(0u), ior, entering);
            EXPECT_EQ(eta, entering ? 1.0f / ior : ior);
            for (double theta : incidence_angles(eta)) {
                SCOPED_TRACE(fmt::format("ior {} {}, theta {:.10f}", ior, entering ? "in" : "out", theta));
                const vec3 d(float(std::sin(theta)), 0.0f, float(-std::cos(theta)));
                const Kernel::Refraction r = k.refract_fresnel(d, vec3(0.0f, 0.0f, 1.0f), eta);
                const Power exact = fresnel_power(double(-d.z), double(eta));
                const double e = double(eta), c = double(d.z);
                ++samples;
                ASSERT_TRUE(std::isfinite(r.reflectance));
                ASSERT_GE(r.reflectance, 0.0f);
                ASSERT_LE(r.reflectance, 1.0f);
                if (!exact.total) {
                    EXPECT_NEAR(exact.r + exact.t, 1.0, 1e-12);
                }
                // Light never totally reflects on entering a denser medium.
                if (eta <= 1.0f) {
                    ASSERT_FALSE(r.total);
                }
                // The kernel's weights: R reflected, 1 - R refracted, summed in float.
                const float refracted = 1.0f - r.reflectance;
                worst_weights = std::max(worst_weights, std::abs(double(r.reflectance) + double(refracted) - 1.0));
                EXPECT_EQ(r.reflectance + refracted, 1.0f);
                if (r.total) {
                    ++totals;
                    EXPECT_EQ(r.reflectance, 1.0f);
                } else {
                    ASSERT_TRUE(std::isfinite(r.dir.x) && std::isfinite(r.dir.y) && std::isfinite(r.dir.z));
                    EXPECT_NEAR(glm::length(r.dir), 1.0, 1e-6);
                    EXPECT_LE(r.dir.z, 0.0f);
                    // Snell: sin(theta_t) = eta sin(theta_i).
                    const double snell = std::abs(double(r.dir.x) - double(eta) * double(d.x));
                    worst_snell = std::max(worst_snell, snell);
                    EXPECT_LE(snell, 1e-6);
                }
                // The total-reflection decision is the exact one except within float
                // rounding of cos^2(theta_t) = 0 (1e-6: a few ULPs of eta^2).
                if (std::abs((1.0 - e) * (1.0 + e) + e * e * c * c) > 1e-6) {
                    EXPECT_EQ(r.total, exact.total);
                }
                // Energy: the kernel's R against the exact T. Where cos_t is small the
                // problem itself is ill-conditioned (R has a square-root singularity
                // at the critical angle, and the input direction carries float
                // rounding), so the bound there follows sqrt(float epsilon).
                const double error = std::abs(double(r.reflectance) + exact.t - 1.0);
                const bool near_critical = exact.total || r.total || exact.cos_t < 0.01;
                (near_critical ? worst_near : worst_far) = std::max(near_critical ? worst_near : worst_far, error);
                if (!near_critical) {
                    worst_scaled = std::max(worst_scaled, error * exact.cos_t / std::max(1.0, e * e));
                }
                EXPECT_LE(error, near_critical ? 2e-3 : 1e-6 + 1e-6 * std::max(1.0, e * e) / exact.cos_t);
            }
        }
    }
    std::printf("[ measured ] %d incidences, %d totally reflected: max |R + T - 1| %.3g (cos_t >= 0.01), "
                "%.3g (near the critical angle), error * cos_t / max(1, eta^2) %.3g; max |R + (1 - R) - 1| in float "
                "%.3g; max Snell error %.3g\n",
                samples, totals, worst_far, worst_near, worst_scaled, worst_weights, worst_snell);
}

// An interface of eta 1 (nested glass of equal ior, or ior 1 in air) is no interface:
// nothing reflects and the ray goes on bit for bit, at every angle up to grazing,
// where 1 - cos_i^2 rounds to 1 and the general formula would reflect it all.
TEST(Refraction, AnInterfaceOfEqualIndicesIsInvisible) {
    Kernel k;
    for (double theta : incidence_angles(1.0)) {
        SCOPED_TRACE(fmt::format("theta {:.10f}", theta));
        const vec3 d = k.unit_vector(vec3(float(std::sin(theta)), 0.3f, float(-std::cos(theta))));
        const Kernel::Refraction r = k.refract_fresnel(d, vec3(0.0f, 0.0f, 1.0f), 1.0f);
        ASSERT_FALSE(r.total);
        ASSERT_EQ(r.reflectance, 0.0f);
        ASSERT_EQ(r.dir, d);
    }
    // Equal indices on both sides of a nested interface make eta exactly 1: two
    // materials of one ior, one body inside the other.
    std::vector<kernel::Material> materials(2);
    materials[0].ior = materials[1].ior = 1.5f;
    k.materials = materials;
    const glm::uvec4 in_glass = k.media_enter(glm::uvec4(0u), 0u);
    EXPECT_EQ(k.interface_eta(in_glass, 1.5f, true), 1.0f);
    const glm::uvec4 in_inner = k.media_enter(in_glass, 1u);
    EXPECT_EQ(k.interface_eta(in_inner, 1.5f, false), 1.0f);
    EXPECT_EQ(k.media_leave(in_inner), in_glass);
    EXPECT_EQ(k.interface_eta(in_glass, 1.5f, false), 1.5f);
    EXPECT_EQ(k.media_leave(in_glass), glm::uvec4(0u));
}

// ------------------------------------------------------ case 7: nested glass

// A glass sphere inside a glass sphere of the same ior (another material, equal
// values) against the outer sphere alone. The inner interface has eta 1 (R = 0,
// straight through), so the images differ only where the extra crossing's offset
// (up to 256 ULPs of the hit point) flips a decision, or where the two extra
// generations it takes meet max_depth. An inner sphere of ior 1.3 is the control:
// a visible interface that the comparison must see.
struct NestedImages {
    float largest;     // the largest channel difference, nested against single
    double agreeing;   // pixels whose channels all agree within 1e-4
    float lens;        // the largest difference of the ior-1.3 control against single
};

NestedImages compare_nested(const std::string& file, bool fresnel, RenderOutcome (*render)(const Scene&)) {
    Scene nested = stability_scene(file);
    for (Material& m : nested.materials) m.fresnel = m.fresnel || fresnel;
    Scene single = nested;
    single.spheres.erase(single.spheres.begin() + 1);
    Scene lens = nested;
    lens.materials[lens.spheres[1].material].ior = 1.3;
    const RenderOutcome a = render(nested);
    const RenderOutcome b = render(single);
    const RenderOutcome c = render(lens);
    test::expect_sane(a);
    test::expect_sane(b);
    test::expect_sane(c);
    return {test::max_abs_difference(a.image, b.image), agreeing(a.image, b.image, 1e-4f),
            test::max_abs_difference(c.image, b.image)};
}

class NestedGlass : public ::testing::TestWithParam<std::string> {};

TEST_P(NestedGlass, RendersLikeOneBodyOnBothBackends) {
    for (bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "vulkan" : "cpu");
        const NestedImages m = compare_nested(GetParam(), false, vulkan ? test::render_vulkan : test::render_cpu);
        std::printf("[ measured ] %s on %s: nested vs single: largest difference %.3g, %.4f of pixels within "
                    "1e-4; the ior-1.3 control differs by up to %.3g\n",
                    GetParam().c_str(), vulkan ? "vulkan" : "cpu", m.largest, m.agreeing, m.lens);
        EXPECT_GT(m.lens, 0.05f);
        EXPECT_GE(m.agreeing, 0.99);
        EXPECT_LE(m.largest, 1e-4f);
    }
}

// With Fresnel weights every glass hit also spawns a reflected ray, and the deepest
// generations of the tree are cut by max_depth: a path through the inner sphere uses
// two more generations per pass, so the nested image lacks some of the single body's
// deepest light. Bounded by what the single body itself loses when cut 4 generations
// earlier (two passes).
TEST(NestedGlass, WithFresnelDiffersOnlyByTheGenerationsItUses) {
    const NestedImages m = compare_nested("case7_nested_glass_local.json", true, test::render_cpu);
    Scene deep = stability_scene("case7_nested_glass_local.json");
    for (Material& material : deep.materials) material.fresnel = true;
    deep.spheres.erase(deep.spheres.begin() + 1);
    Scene shallow = deep;
    shallow.render.max_depth = deep.render.max_depth - 4;
    const float cut = test::max_abs_difference(test::render_cpu(deep).image, test::render_cpu(shallow).image);
    std::printf("[ measured ] fresnel on: nested vs single: largest difference %.3g, %.4f of pixels within 1e-4; "
                "the single body cut 4 generations earlier: %.3g\n", m.largest, m.agreeing, cut);
    EXPECT_LE(m.largest, cut);
}

INSTANTIATE_TEST_SUITE_P(Stability, NestedGlass,
                         ::testing::Values("case7_nested_glass_local.json", "case7_nested_glass_global.json"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             return param.param.find("global") != std::string::npos ? "global_paper" : "local";
                         });

// ----------------------------------------- case 7: a slab that traps its rays

// The eye inside a glass slab (two 20,000-wide parallel faces, 1 apart), looking 21 to
// 41 degrees down: every ray meets a face at 49 degrees or more from its normal,
// beyond the critical angle of 41.8, and is reflected for ever. Fresnel off: the
// trapped rays keep weight 1, so nothing but the limits can end them.
void expect_same_counts(const RenderStats& a, const RenderStats& b) {
    EXPECT_EQ(a.reflection_rays, b.reflection_rays);
    EXPECT_EQ(a.refraction_rays, b.refraction_rays);
    EXPECT_EQ(a.bounce_rays, b.bounce_rays);
    EXPECT_EQ(a.roulette_ended, b.roulette_ended);
    EXPECT_EQ(a.paper_dropped, b.paper_dropped);
}

TEST(TrappedRays, TheRayTreeEndsAtMaxDepth) {
    const Scene scene = stability_scene("case7_slab_trap_local.json");
    ASSERT_EQ(scene.render.max_depth, 64u);
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome vulkan = test::render_vulkan(scene);
    for (const RenderOutcome* out : {&cpu, &vulkan}) {
        test::expect_sane(*out);
        // Total internal reflection spawns no refracted ray; each eye ray has exactly
        // 64 reflected descendants, one a generation, and then the tree ends.
        EXPECT_EQ(out->stats.refraction_rays, 0u);
        EXPECT_EQ(out->stats.reflection_rays, 64u * out->stats.eye_rays);
        EXPECT_EQ(out->stats.eye_hits, out->stats.eye_rays);
        EXPECT_EQ(out->stats.dropped_stack_full, 0u);
    }
    expect_same_counts(cpu.stats, vulkan.stats);
    EXPECT_EQ(test::max_abs_difference(cpu.image, vulkan.image), 0.0f);
    std::printf("[ measured ] slab, local: %llu eye rays, %llu reflection rays, 0 refracted\n",
                static_cast<unsigned long long>(cpu.stats.eye_rays),
                static_cast<unsigned long long>(cpu.stats.reflection_rays));
}

TEST(TrappedRays, PathsEndByRouletteOrMaxBounces) {
    // Path tracing: throughput 1 survives roulette with probability 0.95 a bounce,
    // so every path ends by roulette long before max_bounces 1000.
    const Scene path = stability_scene("case7_slab_trap_global.json");
    ASSERT_EQ(path.render.max_bounces, 1000u);
    const RenderOutcome cpu = test::render_cpu(path);
    const RenderOutcome vulkan = test::render_vulkan(path);
    for (const RenderOutcome* out : {&cpu, &vulkan}) {
        test::expect_sane(*out);
        EXPECT_EQ(out->stats.roulette_ended, out->stats.eye_rays);
        EXPECT_LT(out->stats.bounce_rays, 100u * out->stats.eye_rays);
        // No trapped ray ever sees the sky.
        EXPECT_EQ(test::max_abs_difference(out->image, Image(out->image.width, out->image.height)), 0.0f);
    }
    expect_same_counts(cpu.stats, vulkan.stats);
    std::printf("[ measured ] slab, path: %llu paths, %llu bounces (%.1f a path), all ended by roulette\n",
                static_cast<unsigned long long>(cpu.stats.eye_rays),
                static_cast<unsigned long long>(cpu.stats.bounce_rays),
                double(cpu.stats.bounce_rays) / double(cpu.stats.eye_rays));
    // The paper's estimator follows glass without roulette: every sample meets
    // exactly max_bounces = 1000 faces, is then dropped (its gl() is 0), and ends.
    const Scene paper = stability_scene("case7_slab_trap_paper.json");
    const RenderOutcome cpu_paper = test::render_cpu(paper);
    const RenderOutcome vulkan_paper = test::render_vulkan(paper);
    for (const RenderOutcome* out : {&cpu_paper, &vulkan_paper}) {
        EXPECT_EQ(test::nonfinite_values(out->image), 0u);
        EXPECT_EQ(out->stats.truncated_samples, 0u);
        EXPECT_EQ(out->stats.paper_dropped, out->stats.eye_rays);
        EXPECT_EQ(out->stats.bounce_rays, 1000u * out->stats.eye_rays);
    }
    expect_same_counts(cpu_paper.stats, vulkan_paper.stats);
}

// ------------------------------------------- case 10: the basis, on the device

// A grey disc (diffuse 0.5) under a white sky, one bounce, cosine sampling: each
// sample is 0.5 cos(theta) / pi / (cos(theta) / pi) times the sky, 0.5 to rounding,
// whatever direction the basis around the normal makes, as long as the direction is
// above the surface and finite. A basis that divides by zero (the sign(-0) = 0 trap)
// gives NaN samples, discarded and counted; one not orthogonal to the normal sends
// samples below the surface, which end the path at 0. Pixels are 0.5 on the disc, 1
// off it, and multiples of 1/8 between (4 jittered samples).
Scene disc_facing(glm::dvec3 normal, bool from_front) {
    Scene scene = stability_scene("case10_basis_near_minus_z.json");
    scene.rings[0].normal = normal;
    scene.camera.eye = (from_front ? 3.0 : -3.0) * normal;
    scene.camera.up = std::abs(normal.y) > 0.5 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    return scene;
}

void expect_disc_image(const Image& image) {
    for (std::size_t i = 0; i < image.rgb.size(); ++i) {
        const float eighths = std::round(image.rgb[i] * 8.0f);
        ASSERT_GE(eighths, 4.0f) << "value " << image.rgb[i] << " at " << i;
        ASSERT_NEAR(image.rgb[i], eighths / 8.0f, 1e-5f) << "at " << i;
    }
    const std::size_t centre = 3 * (std::size_t(image.height / 2) * image.width + image.width / 2);
    EXPECT_NEAR(image.rgb[centre], 0.5f, 1e-5f);
}

TEST(HemisphereBasis, AxisAndSignedZeroNormalsSampleAboveTheSurfaceOnBothBackends) {
    struct Case {
        glm::dvec3 normal;
        bool from_front;
    };
    std::vector<Case> cases;
    for (int axis = 0; axis < 3; ++axis) {
        for (double sign : {1.0, -1.0}) {
            for (double zero : {0.0, -0.0}) {
                glm::dvec3 n(zero);
                n[axis] = sign;
                cases.push_back({n, true});
            }
        }
    }
    // Near -z, where the classic frames divide by almost nothing, and -z reached as
    // the back face of a +z disc: the hit normal is then (-0, -0, -1).
    cases.push_back({glm::normalize(glm::dvec3(1e-7, 0.0, -1.0)), true});
    cases.push_back({glm::dvec3(0.0, -0.0, -1.0), true});
    cases.push_back({glm::dvec3(-0.0, -0.0, -1.0), true});
    cases.push_back({glm::dvec3(0.0, 0.0, 1.0), false});
    for (const Case& c : cases) {
        SCOPED_TRACE(fmt::format("normal ({}, {}, {}) seen from the {}", c.normal.x, c.normal.y, c.normal.z,
                                 c.from_front ? "front" : "back"));
        const Scene scene = disc_facing(c.normal, c.from_front);
        const RenderOutcome cpu = test::render_cpu(scene);
        const RenderOutcome vulkan = test::render_vulkan(scene);
        test::expect_sane(cpu);
        test::expect_sane(vulkan);
        expect_disc_image(cpu.image);
        expect_disc_image(vulkan.image);
        EXPECT_LE(test::max_abs_difference(cpu.image, vulkan.image), 1e-5f);
    }
}

// The shipped files keep their signed zeros through the loader.
TEST(HemisphereBasis, TheSceneFilesHoldTheirNormals) {
    const Scene zeros = stability_scene("case10_basis_minus_z_signed_zeros.json");
    EXPECT_TRUE(std::signbit(zeros.rings[0].normal.x));
    EXPECT_TRUE(std::signbit(zeros.rings[0].normal.y));
    EXPECT_EQ(zeros.rings[0].normal.z, -1.0);
    for (const char* file : {"case10_basis_minus_z_signed_zeros.json", "case10_basis_near_minus_z.json"}) {
        SCOPED_TRACE(file);
        const RenderOutcome cpu = test::render_cpu(stability_scene(file));
        test::expect_sane(cpu);
        expect_disc_image(cpu.image);
    }
}

}  // namespace
}  // namespace vkrt
