// Camera rays, sub-pixel positions and random numbers of the shared kernel.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "kernel/kernel.hpp"
#include "flatten/flat_scene.hpp"
#include "statistics.hpp"

namespace {

using vkrt::kernel::Kernel;
using vkrt::kernel::uint;
using vkrt::kernel::uvec4;
using vkrt::kernel::vec2;
using vkrt::kernel::vec3;

// A camera at the origin looking down -z with a 90 degree vertical field of view on
// a 4x2 image: one pixel is exactly one unit on the image plane at distance 1; with
// a lens of the given radius, in focus at `focus`.
Kernel kernel_for_camera(std::uint32_t aa = 1, bool jitter = false, double lens_radius = 0.0, double focus = 1.0) {
    vkrt::Scene scene;
    scene.camera.eye = {0, 0, 0};
    scene.camera.look_at = {0, 0, -1};
    scene.camera.fov = 90;
    scene.camera.width = 4;
    scene.camera.height = 2;
    scene.render.aa = aa;
    scene.render.jitter = jitter;
    scene.camera.lens_radius = lens_radius;
    scene.camera.focus_distance = focus;
    Kernel k;
    k.params = vkrt::flatten_scene(scene).params;
    k.HAS_JITTER = jitter;
    return k;
}

TEST(Camera, CentreOfImageLooksAtTarget) {
    Kernel k = kernel_for_camera();
    const auto r = k.camera_ray(2.0f, 1.0f);
    EXPECT_EQ(r.origin, vec3(0));
    EXPECT_EQ(r.dir, vec3(0, 0, -1));
}

TEST(Camera, TopLeftCornerIsUpAndLeft) {
    Kernel k = kernel_for_camera();
    // Image position (0, 0) is the top-left corner: direction (-2, 1, -1).
    const auto r = k.camera_ray(0.0f, 0.0f);
    const float s = 1.0f / std::sqrt(6.0f);
    EXPECT_FLOAT_EQ(r.dir.x, -2.0f * s);
    EXPECT_FLOAT_EQ(r.dir.y, 1.0f * s);
    EXPECT_FLOAT_EQ(r.dir.z, -1.0f * s);
}

TEST(Camera, RowsGrowDownwards) {
    Kernel k = kernel_for_camera();
    EXPECT_GT(k.camera_ray(0.5f, 0.5f).dir.y, 0.0f);
    EXPECT_LT(k.camera_ray(0.5f, 1.5f).dir.y, 0.0f);
    EXPECT_LT(k.camera_ray(0.5f, 0.5f).dir.x, k.camera_ray(3.5f, 0.5f).dir.x);
}

// A lens of radius 0.5 in focus at 3: every ray of a pixel leaves the lens disc and
// passes through the pinhole ray's point on the plane in focus.
TEST(ThinLens, RaysOfOnePixelMeetOnThePlaneInFocus) {
    Kernel k = kernel_for_camera(1, false, 0.5, 3.0);
    for (const vec2 pixel : {vec2(2.0f, 1.0f), vec2(0.25f, 0.5f), vec2(3.5f, 1.75f)}) {
        const Kernel::Ray pinhole = k.camera_ray(pixel.x, pixel.y);
        const vec3 focus = pinhole.origin + (3.0f / -pinhole.dir.z) * pinhole.dir;
        for (const vec2 u : {vec2(0.5f), vec2(0.9f, 0.1f), vec2(0.0f, 0.3f), vec2(0.7f, 1.0f)}) {
            const Kernel::Ray r = k.camera_ray(pixel.x, pixel.y, u);
            EXPECT_EQ(r.origin.z, 0.0f) << "on the lens";
            EXPECT_LE(std::hypot(r.origin.x, r.origin.y), 0.5f + 1e-6f) << "within its radius";
            EXPECT_NEAR(glm::length(r.dir), 1.0f, 1e-6f);
            const vec3 at = r.origin + (3.0f / -r.dir.z) * r.dir;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(at[c], focus[c], 2e-6f) << "lens point " << u.x << ", " << u.y;
        }
    }
    // The lens's edge: u = (1, 0.5) is its rightmost point, +x.
    const Kernel::Ray edge = k.camera_ray(2.0f, 1.0f, vec2(1.0f, 0.5f));
    EXPECT_NEAR(edge.origin.x, 0.5f, 1e-6f);
    EXPECT_NEAR(edge.origin.y, 0.0f, 1e-6f);
}

TEST(ThinLens, WithoutARadiusItIsThePinhole) {
    Kernel k = kernel_for_camera(1, false, 0.0, 3.0);
    const Kernel::Ray a = k.camera_ray(0.25f, 1.5f, vec2(0.9f, 0.2f));
    const Kernel::Ray b = k.camera_ray(0.25f, 1.5f);
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.dir, b.dir);
}

TEST(Subpixel, RegularGridCentresWithoutJitter) {
    Kernel k = kernel_for_camera(3);
    auto rng = k.rng_start(0, 0, 0);
    const auto first = k.subpixel_position(0, rng);
    EXPECT_FLOAT_EQ(first.x, 0.5f / 3.0f);
    EXPECT_FLOAT_EQ(first.y, 0.5f / 3.0f);
    const auto centre = k.subpixel_position(4, rng);
    EXPECT_FLOAT_EQ(centre.x, 0.5f);
    EXPECT_FLOAT_EQ(centre.y, 0.5f);
    const auto fifth = k.subpixel_position(5, rng);  // column 2, row 1
    EXPECT_FLOAT_EQ(fifth.x, 2.5f / 3.0f);
    EXPECT_FLOAT_EQ(fifth.y, 1.5f / 3.0f);
    const auto wrapped = k.subpixel_position(9, rng);  // sample 9 reuses stratum 0
    EXPECT_EQ(wrapped.x, first.x);
    EXPECT_EQ(wrapped.y, first.y);
    EXPECT_EQ(rng.dim, 0u);  // no random numbers drawn without jitter
}

TEST(Subpixel, JitterStaysInsideItsStratum) {
    Kernel k = kernel_for_camera(2, true);
    for (uint s = 0; s < 400; ++s) {
        auto rng = k.rng_start(7, s, 0);
        const auto p = k.subpixel_position(s, rng);
        const uint stratum = s % 4;
        EXPECT_GE(p.x, float(stratum % 2) * 0.5f);
        EXPECT_LT(p.x, float(stratum % 2 + 1) * 0.5f);
        EXPECT_GE(p.y, float(stratum / 2) * 0.5f);
        EXPECT_LT(p.y, float(stratum / 2 + 1) * 0.5f);
        EXPECT_EQ(rng.dim, 1u);  // the camera's one slot
    }
}

// pcg4d transcribed independently from Jarzynski & Olano (JCGT 2020), listing 4,
// on plain integers: the kernel must produce exactly these bits.
std::uint32_t pcg4d_x(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    std::uint32_t v[4] = {a, b, c, d};
    for (auto& e : v) e = e * 1664525u + 1013904223u;
    auto mix = [&] {
        v[0] += v[1] * v[3];
        v[1] += v[2] * v[0];
        v[2] += v[0] * v[1];
        v[3] += v[1] * v[2];
    };
    mix();
    for (auto& e : v) e ^= e >> 16u;
    mix();
    return v[0];
}

TEST(Rng, MatchesThePublishedHash) {
    Kernel k;
    auto rng = k.rng_start(12345u, 67u, 89u);
    for (uint dim = 0; dim < 8; ++dim) {
        const float expected = float(pcg4d_x(12345u, 67u, 89u, dim) >> 8) / 16777216.0f;
        EXPECT_EQ(k.rng_next(rng), expected) << "dimension " << dim;
    }
}

// The numerical-stability suite, case 11: whatever the hash, the float stays below 1. The top 256 hashes all
// give the largest value, 1 - 2^-24; converting all 32 bits instead would round them
// (and every hash from 2^32 - 128 on) to exactly 1.0.
TEST(Rng, UnitFloatNeverReachesOne) {
    Kernel k;
    EXPECT_EQ(k.unit_float(0u), 0.0f);
    EXPECT_EQ(k.unit_float(0x100u), 0x1p-24f);
    for (std::uint32_t h = 0xFFFFFF00u; h != 0u; ++h) ASSERT_EQ(k.unit_float(h), 1.0f - 0x1p-24f) << h;
    EXPECT_EQ(float(0xFFFFFFFFu) * 0x1p-32f, 1.0f);  // the trap this avoids
    for (std::uint32_t h = 0x80u; h < 0xFFFFFFFFu - 0x3FFFFFu; h += 0x3FFFFFu) {
        ASSERT_LT(k.unit_float(h), 1.0f);
        ASSERT_EQ(k.unit_float(h), float(h >> 8) / 16777216.0f);
    }
}

TEST(Rng, UniformInTheHalfOpenUnitInterval) {
    Kernel k;
    constexpr int kBins = 16;
    constexpr int kDraws = 160000;
    std::array<double, kBins> bins{};
    double sum = 0.0;
    for (int i = 0; i < kDraws; ++i) {
        auto rng = k.rng_start(uint(i), 0, 0);
        const float x = k.rng_next(rng);
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
        sum += x;
        bins[int(x * kBins)] += 1.0;
    }
    EXPECT_NEAR(sum / kDraws, 0.5, 0.005);
    // A fair generator fails one run in a thousand.
    std::array<double, kBins> expected;
    expected.fill(double(kDraws) / kBins);
    const vkrt::test::ChiSquareResult fit = vkrt::test::chi_square_test(bins, expected);
    EXPECT_GT(fit.p_value, 1e-3) << fit;
}

}  // namespace
