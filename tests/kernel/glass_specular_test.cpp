// glTF's specular layer on glass (KHR_materials_specular over _transmission;
// kernel/lobes/glass.glsl glass_split): a layer of factor 1 and white colour leaves the
// exact glass untouched (and is not even marked as a layer); any other layer reflects
// F0 + (F90 - F0) w per channel, w being how far the exact Fresnel reflectance has
// risen from its value at normal incidence, with the largest channel's probability,
// and nothing where there is no interface;
// total internal reflection keeps all the light; and on rough glass the layered
// interface's albedo, from two more tables, gives back what its single scattering
// loses. The images these make are in transmission_test.cpp and rough_glass_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "flatten/ggx_albedo.hpp"
#include "flatten/rough_glass_albedo.hpp"
#include "kernel/kernel.hpp"

namespace vkrt {
namespace {

using kernel::Kernel;
using glm::vec3;

// The glass lobe of a clear metallic-roughness glass of ior 1.5 whose specular layer
// has `factor` and `color`, as the host writes it (flat_scene.cpp).
Kernel::GlassLobe layered_glass(Kernel& k, float factor, vec3 color) {
    kernel::Material m{};
    m.ior = 1.5f;
    m.dielectric_f0 = 0.04f;
    m.dielectric_f0_rgb = glm::min(vec3(0.04f) * color, vec3(1.0f)) * factor;
    m.dielectric_f90 = factor;
    m.transmission = 1.0f;
    m.ggx_alpha = 0.25f;
    return k.glass_lobe(m);
}

TEST(GlassSpecular, TheDefaultLayerIsTheExactGlass) {
    Kernel k;
    const Kernel::GlassLobe plain = layered_glass(k, 1.0f, vec3(1.0f));
    EXPECT_FALSE(plain.layered);
    for (const float r : {0.0f, 0.04f, 0.3f, 1.0f}) {
        const Kernel::GlassSplit s = k.glass_split(plain, r, 1.0f / 1.5f);
        EXPECT_EQ(s.p_reflect, r);
        EXPECT_EQ(s.tint, vec3(1.0f));
    }
    EXPECT_TRUE(layered_glass(k, 0.5f, vec3(1.0f)).layered);
    EXPECT_TRUE(layered_glass(k, 1.0f, vec3(1.0f, 1.0f, 0.5f)).layered);
}

// Factor 0.5, colour (4, 1, 0.25): F0 = (0.08, 0.02, 0.005), F90 = 0.5.
TEST(GlassSpecular, TheLayerReflectsItsOwnReflectance) {
    Kernel k;
    const Kernel::GlassLobe g = layered_glass(k, 0.5f, vec3(4.0f, 1.0f, 0.25f));
    for (const float eta : {1.0f / 1.5f, 1.5f}) {
        SCOPED_TRACE(testing::Message() << "eta " << eta);
        const float f0 = std::pow((1.0f - eta) / (1.0f + eta), 2.0f);
        // At the interface's normal-incidence reflectance, from either side: F0.
        const Kernel::GlassSplit head_on = k.glass_split(g, f0, eta);
        EXPECT_FLOAT_EQ(head_on.p_reflect, 0.08f);
        EXPECT_FLOAT_EQ(head_on.tint.x, 1.0f);
        EXPECT_FLOAT_EQ(head_on.tint.y, 0.25f);
        EXPECT_FLOAT_EQ(head_on.tint.z, 0.0625f);
        // Halfway from f0 to 1: halfway from F0 to F90.
        const Kernel::GlassSplit half = k.glass_split(g, f0 + 0.5f * (1.0f - f0), eta);
        EXPECT_NEAR(half.p_reflect, 0.29f, 1e-6f);
        EXPECT_NEAR(half.tint.y, 0.26f / 0.29f, 1e-6f);
        EXPECT_NEAR(half.tint.z, 0.2525f / 0.29f, 1e-6f);
        // Near grazing incidence the layer reflects its factor, F90, in every channel.
        const Kernel::GlassSplit grazing = k.glass_split(g, 0.999999f, eta);
        EXPECT_NEAR(grazing.p_reflect, 0.5f, 1e-6f);
        EXPECT_NEAR(grazing.tint.z, 1.0f, 1e-5f);
    }
    // Where there is no interface (nested glass of one ior), nothing reflects.
    EXPECT_EQ(k.glass_split(g, 0.0f, 1.0f).p_reflect, 0.0f);
    // Total internal reflection reflects all of it, untinted.
    const Kernel::GlassSplit total = k.glass_split(g, 1.0f, 1.5f);
    EXPECT_EQ(total.p_reflect, 1.0f);
    EXPECT_EQ(total.tint, vec3(1.0f));
    // A layer of factor 0 never reflects (but by total internal reflection).
    const Kernel::GlassSplit none = k.glass_split(layered_glass(k, 0.0f, vec3(1.0f)), 0.3f, 1.0f / 1.5f);
    EXPECT_EQ(none.p_reflect, 0.0f);
}

// Rough glass divides each crossing's weight by the interface's albedo (rough_glass.glsl).
// Under a white layer the microfacet still passes all of its light one way or the
// other, only in another split between the ways, whose G2/G1 differ, so the exact
// glass's E would be wrong (it kept 0.95 to 1.08 of the light at roughness 1): the
// layered albedo from the tables D1 and DR must match quadrature of the layered
// glass's single scattering (in its largest channel for a coloured layer, the one
// reflected with weight 1), for entering and leaving glass, within 1.2% as E does.
TEST(GlassSpecular, RoughGlassUnderALayerKeepsTheLight) {
    static const std::vector<std::uint32_t> words = [] {
        std::vector<std::uint32_t> w = ggx_albedo_table();
        for (const auto* tables : {&rough_glass_albedo_table(), &rough_glass_layer_tables()}) {
            w.insert(w.end(), tables->begin(), tables->end());
        }
        return w;
    }();
    Kernel k;
    k.HAS_SHEEN = false;
    k.table_words = words;
    kernel::set_ggx_table_first_word(k.params, 0u);
    double worst = 0.0;
    const std::pair<float, vec3> layers[] = {{0.0f, vec3(1.0f)}, {0.5f, vec3(1.0f)}, {1.0f, vec3(4.0f, 1.0f, 0.25f)}};
    for (const auto& [factor, colour] : layers) {
        Kernel::GlassLobe g = layered_glass(k, factor, colour);
        for (const float eta : {1.0f / 1.5f, 1.5f}) {
            for (const float roughness : {0.3f, 0.7f, 1.0f}) {
                const float alpha = roughness * roughness;
                g.alpha = alpha;
                for (const float mu : {1.0f, 0.5f, 0.15f}) {
                    const vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
                    const int side = 96;
                    double sum = 0.0;
                    for (int a = 0; a < side; ++a) {
                        for (int b = 0; b < side; ++b) {
                            const auto c = k.rough_crossing(alpha, eta, false, wo, (a + 0.5f) / side, (b + 0.5f) / side);
                            const double p = k.glass_split(g, c.reflectance, eta).p_reflect;
                            sum += p * c.reflect_weight + (1.0 - p) * c.refract_weight;
                        }
                    }
                    const float e = k.rough_glass_albedo(mu, alpha, eta, false);
                    const double kept = sum / (double(side) * side) / k.rough_glass_layered_albedo(e, g, mu, eta);
                    std::printf("factor %.1f colour %.2f %.2f %.2f eta %.3f roughness %.1f cos_o %.2f: kept %.4f\n",
                                factor, colour.x, colour.y, colour.z, eta, roughness, mu, kept);
                    EXPECT_NEAR(kept, 1.0, 0.012);
                    worst = std::max(worst, std::abs(kept - 1.0));
                }
            }
        }
    }
    std::printf("worst: %.4f from 1\n", worst);
}

}  // namespace
}  // namespace vkrt
