// KHR_materials_pbrSpecularGlossiness as vkrt's metallic-roughness material
// (host/scene/gltf_spec_gloss.cpp, decision 0033): the factors convert to the values
// the record states, the converted material keeps the extension's reflectance at
// normal incidence and diffuse colour, a hand-written file (tests/scenes/gltf/) is
// read so, and the record's measurement: each model's reflectance by angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include <glm/geometric.hpp>

#include "ggx_reference.hpp"
#include "scene/gltf_spec_gloss.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace {

using glm::dvec3;
using vkrt::Material;
using vkrt::gltf::SpecularGlossiness;
using vkrt::gltf::to_metallic_roughness;
namespace ggx = vkrt::test::ggx;

// ------------------------------------------------------------------ the conversion

void expect_material(const Material::MetallicRoughness& mr, dvec3 base, double metallic, double roughness) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(mr.base_color[k], base[k], 1e-12) << "base colour " << k;
    EXPECT_NEAR(mr.metallic, metallic, 1e-12);
    EXPECT_NEAR(mr.roughness, roughness, 1e-12);
}

// The values of decision 0033's table.
TEST(SpecularGlossiness, FactorsConvertToTheRecordsValues) {
    // A dielectric (F0 below 0.04): the base colour is the diffuse colour, c_diff / 0.96.
    expect_material(to_metallic_roughness({dvec3(0.8, 0.2, 0.1), dvec3(0.04), 0.5}), dvec3(0.8, 0.2, 0.1), 0.0, 0.5);
    // The extension's gold: no diffuse colour, a metal of the specular colour.
    expect_material(to_metallic_roughness({dvec3(0.0), dvec3(1.0, 0.766, 0.336), 0.9}), dvec3(1.0, 0.766, 0.336), 1.0,
                    0.1);
    // The extension's defaults (every factor 1): a white, polished metal.
    expect_material(to_metallic_roughness({}), dvec3(1.0), 1.0, 0.0);
    // Grey, diffuse 0.5 and specular 0.2: c_diff 0.4, F0 0.2; the metallic factor
    // solves 0.04 m^2 + (0.4 / 0.96 + 0.2 - 0.08) m - 0.16 = 0; the base colour
    // blends 0.4 / (0.96 (1 - m)) and (0.2 - 0.04 (1 - m)) / m by m^2.
    expect_material(to_metallic_roughness({dvec3(0.5), dvec3(0.2), 0.5}), dvec3(0.58833829360685708),
                    0.29179067350476734, 0.5);
    expect_material(to_metallic_roughness({dvec3(0.5), dvec3(0.5), 0.5}), dvec3(0.74646194774477459),
                    0.65113202695269012, 0.5);
    // Coloured: the metallic factor is solved on perceived brightness.
    expect_material(to_metallic_roughness({dvec3(0.3, 0.1, 0.05), dvec3(0.6, 0.35, 0.2), 0.3}),
                    dvec3(0.73471483129542658, 0.36868354047535634, 0.20296750393007035), 0.84809387246021073, 0.7);
}

// A texel multiplies each factor by its texture's value (the glossiness by the
// specular-glossiness texture's alpha) before the conversion: the grey material
// of above, from a texel of half the diffuse factor's colour and a specular
// texel of 0.8 under a factor of 0.25.
TEST(SpecularGlossiness, ATexelTimesItsFactorsConverts) {
    const SpecularGlossiness factors{dvec3(1.0), dvec3(0.25), 1.0};
    expect_material(vkrt::gltf::convert_texel(dvec3(0.5), glm::dvec4(0.8, 0.8, 0.8, 0.5), factors),
                    dvec3(0.58833829360685708), 0.29179067350476734, 0.5);
    // Absent textures count as 1: the factors' own conversion.
    const SpecularGlossiness gold{dvec3(0.0), dvec3(1.0, 0.766, 0.336), 0.9};
    const Material::MetallicRoughness a = vkrt::gltf::convert_texel(dvec3(1.0), glm::dvec4(1.0), gold);
    const Material::MetallicRoughness b = to_metallic_roughness(gold);
    EXPECT_EQ(a.base_color, b.base_color);
    EXPECT_EQ(a.metallic, b.metallic);
    EXPECT_EQ(a.roughness, b.roughness);
}

// In glTF's reference model the converted material reflects mix(0.04, base, m) at
// normal incidence and has the diffuse colour 0.96 (1 - m) base: for grey factors,
// the extension's F0 = specular and c_diff = diffuse (1 - max(specular)) exactly.
TEST(SpecularGlossiness, GreyFactorsKeepTheExtensionsReflectanceAndDiffuseColour) {
    for (const double diffuse : {0.0, 0.2, 0.5, 0.9, 1.0}) {
        for (const double specular : {0.04, 0.1, 0.2, 0.5, 0.8}) {
            const Material::MetallicRoughness mr = to_metallic_roughness({dvec3(diffuse), dvec3(specular), 0.5});
            if (mr.base_color.r >= 1.0) continue;  // clamped: brighter than the material can be
            const double f0 = 0.04 + (mr.base_color.r - 0.04) * mr.metallic;
            const double c_diff = 0.96 * (1.0 - mr.metallic) * mr.base_color.r;
            EXPECT_NEAR(f0, specular, 1e-12) << diffuse << ", " << specular;
            EXPECT_NEAR(c_diff, diffuse * (1.0 - specular), 1e-12) << diffuse << ", " << specular;
        }
    }
}

// ------------------------------------------------------------------ the file

std::filesystem::path spec_gloss_file() { return vkrt::test::source_dir() / "tests" / "scenes" / "gltf" / "spec_gloss.gltf"; }

const Material& material_named(const vkrt::Scene& s, const std::string& name) {
    for (const Material& m : s.materials) {
        if (m.name == name) return m;
    }
    ADD_FAILURE() << "no material " << name;
    return s.materials.front();
}

TEST(SpecularGlossiness, AFileIsReadWithTheConvertedMaterials) {
    const vkrt::Scene s = vkrt::load_scene(spec_gloss_file());
    // Factors alone (grey, as above).
    const Material& grey = material_named(s, "grey");
    ASSERT_TRUE(grey.metallic_roughness);
    expect_material(*grey.metallic_roughness, dvec3(0.58833829360685708), 0.29179067350476734, 0.5);
    // The extension takes the place of the material's pbrMetallicRoughness.
    const Material& gold = material_named(s, "gold");
    expect_material(*gold.metallic_roughness, dvec3(1.0, 0.766, 0.336), 1.0, 0.1);
    EXPECT_FALSE(gold.texture) << "pbrMetallicRoughness's texture is not read beside the extension";
    // Its defaults; textures are named as ignored.
    const Material& textured = material_named(s, "defaults with a diffuse texture");
    expect_material(*textured.metallic_roughness, dvec3(1.0), 1.0, 0.0);
    EXPECT_FALSE(textured.texture);
    bool named = false;
    for (const std::string& w : s.warnings) {
        named = named || w.find("KHR_materials_pbrSpecularGlossiness textures (their factors alone are converted) (1)") !=
                             std::string::npos;
    }
    EXPECT_TRUE(named) << "no warning about the ignored texture";
}

TEST(SpecularGlossiness, BadFactorsAreNamed) {
    std::ifstream in(spec_gloss_file());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::filesystem::path dir = vkrt::test::temp_dir("spec_gloss_bad");
    const auto refusal = [&](const std::string& from, const std::string& to) {
        std::string edited = text;
        const std::size_t at = edited.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        edited.replace(at, from.size(), to);
        std::ofstream(dir / "bad.gltf") << edited;
        return vkrt::test::load_error_of(dir / "bad.gltf");
    };
    const std::string element = (dir / "bad.gltf").string() + ": materials[0].extensions.KHR_materials_pbrSpecularGlossiness.";
    EXPECT_EQ(refusal(R"("glossinessFactor": 0.5)", R"("glossinessFactor": 1.5)"),
              element + "glossinessFactor: expected 1 number from 0 to 1");
    EXPECT_EQ(refusal(R"("specularFactor": [0.2, 0.2, 0.2])", R"("specularFactor": [0.2, 0.2])"),
              element + "specularFactor: expected 3 numbers from 0 to 1");
    EXPECT_EQ(refusal(R"("diffuseFactor": [0.5, 0.5, 0.5, 1])", R"("diffuseFactor": [0.5, -0.5, 0.5, 1])"),
              element + "diffuseFactor: expected 4 numbers from 0 to 1");
}

// ------------------------------------------------------------------ the measurement

// The directional albedo of a BRDF seen from cos_o: the integral of f cos_i over the
// hemisphere, taken over the half vector (dw_i = 4 (wo.h) dw_h), 400 x 400 points.
double albedo(const std::function<double(dvec3, dvec3)>& f, double cos_o) {
    const dvec3 wo(std::sqrt(1.0 - cos_o * cos_o), 0.0, cos_o);
    const int n = 400;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double z = (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * ggx::kPi * (j + 0.5) / n;
            const dvec3 h(r * std::cos(phi), r * std::sin(phi), z);
            const double oh = glm::dot(wo, h);
            const dvec3 wi = 2.0 * oh * h - wo;
            if (!(oh > 0.0 && wi.z > 0.0)) continue;
            sum += f(wo, wi) * wi.z * 4.0 * oh * (1.0 / n) * (2.0 * ggx::kPi / n);
        }
    }
    return sum;
}

// GGX's D G2 / (4 cos_o cos_i), of alpha, for unit wo and wi above the surface.
double microfacet(dvec3 wo, dvec3 wi, double alpha) {
    const dvec3 h = glm::normalize(wo + wi);
    return ggx::d(h.z, alpha) * ggx::g2(wo.z, wi.z, alpha) / (4.0 * wo.z * wi.z);
}

double schlick(double f0, dvec3 wo, dvec3 wi) {
    return f0 + (1.0 - f0) * ggx::pow5(1.0 - glm::dot(wo, glm::normalize(wo + wi)));
}

// The extension's own material, one channel: its BRDF inputs in glTF's reference
// BRDF (specification, appendix B), c_diff / pi weighed by 1 - F beside the GGX lobe.
double extension_brdf(double diffuse, double specular, double max_specular, double glossiness, dvec3 wo, dvec3 wi) {
    const double alpha = std::max((1.0 - glossiness) * (1.0 - glossiness), 1e-3);
    const double f = schlick(specular, wo, wi);
    return (1.0 - f) * diffuse * (1.0 - max_specular) / ggx::kPi + f * microfacet(wo, wi, alpha);
}

// Blender's importer: a Diffuse BSDF of the diffuse colour added to a Glossy BSDF
// (GGX, no Fresnel term) of the specular colour, both of roughness 1 - glossiness.
// The diffuse lobe is taken as Lambert's here; Cycles' is Oren-Nayar's.
double blender_brdf(double diffuse, double specular, double glossiness, dvec3 wo, dvec3 wi) {
    const double alpha = std::max((1.0 - glossiness) * (1.0 - glossiness), 1e-3);
    return diffuse / ggx::kPi + specular * microfacet(wo, wi, alpha);
}

// The same conversion solved instead for the diffuse colour of vkrt's own lobe,
// (1 - m) base (1 - F0) (decision 0029), in place of glTF's 0.96 (1 - m) base: the
// alternative decision 0033 measured and did not take.
Material::MetallicRoughness solved_for_vkrt(const SpecularGlossiness& sg) {
    const auto perceived = [](dvec3 c) { return std::sqrt(0.299 * c.r * c.r + 0.587 * c.g * c.g + 0.114 * c.b * c.b); };
    const double oms = 1.0 - std::max({sg.specular.r, sg.specular.g, sg.specular.b});
    const double d = perceived(sg.diffuse) * oms, s = perceived(sg.specular), f0 = std::max(s, 0.04);
    double m = 0.0;
    if (s >= 0.04) {
        const double b = d / (1.0 - s) + s - 0.08, c = 0.04 - s;
        m = std::clamp((-b + std::sqrt(std::max(b * b - 0.16 * c, 0.0))) / 0.08, 0.0, 1.0);
    }
    const dvec3 from_diffuse = sg.diffuse * (oms / std::max((1.0 - m) * (1.0 - f0), 1e-6));
    const dvec3 from_specular = (sg.specular - dvec3(0.04 * (1.0 - m))) / std::max(m, 1e-6);
    return {glm::clamp(glm::mix(from_diffuse, from_specular, m * m), 0.0, 1.0), m, 1.0 - sg.glossiness};
}

// Decision 0033's table: the red channel's albedo at three angles under the
// extension's own model, Blender's sum, and vkrt's material by the reference
// conversion and by the alternative. At normal incidence and at 60 degrees vkrt's
// material by the reference conversion stays within 0.035 of the extension's (the
// plastic's 0.031 is vkrt's diffuse lobe, 21/20 of Lambert's there), and never
// further than by the alternative.
TEST(SpecularGlossiness, ReflectanceByAngleOfEachModel) {
    struct Case {
        const char* name;
        SpecularGlossiness sg;
    };
    const Case cases[] = {{"plastic", {dvec3(0.8, 0.2, 0.1), dvec3(0.04), 0.5}},
                          {"gold", {dvec3(0.0), dvec3(1.0, 0.766, 0.336), 0.5}},
                          {"grey", {dvec3(0.5), dvec3(0.2), 0.5}},
                          {"half", {dvec3(0.5), dvec3(0.5), 0.5}},
                          {"copper", {dvec3(0.3, 0.1, 0.05), dvec3(0.6, 0.35, 0.2), 0.5}}};
    std::printf("material  cos_o  extension  Blender  vkrt (reference)  vkrt (solved for vkrt)\n");
    for (const Case& c : cases) {
        const Material::MetallicRoughness ours = to_metallic_roughness(c.sg), other = solved_for_vkrt(c.sg);
        const double max_specular = std::max({c.sg.specular.r, c.sg.specular.g, c.sg.specular.b});
        for (const double cos_o : {1.0, 0.5, 0.1}) {
            const double extension = albedo(
                [&](dvec3 wo, dvec3 wi) {
                    return extension_brdf(c.sg.diffuse.r, c.sg.specular.r, max_specular, c.sg.glossiness, wo, wi);
                },
                cos_o);
            const double blender = albedo(
                [&](dvec3 wo, dvec3 wi) { return blender_brdf(c.sg.diffuse.r, c.sg.specular.r, c.sg.glossiness, wo, wi); },
                cos_o);
            const auto vkrt = [&](const Material::MetallicRoughness& mr) {
                return albedo(
                    [&](dvec3 wo, dvec3 wi) {
                        return ggx::metallic_roughness_bsdf(mr.base_color.r, mr.metallic, mr.roughness, dvec3(0, 0, 1), wo,
                                                            wi);
                    },
                    cos_o);
            };
            const double a = vkrt(ours), b = vkrt(other);
            std::printf("%-8s  %5.2f  %9.3f  %7.3f  %16.3f  %22.3f\n", c.name, cos_o, extension, blender, a, b);
            if (cos_o >= 0.5) {
                EXPECT_NEAR(a, extension, 0.035) << c.name << " at cos " << cos_o;
                EXPECT_LE(std::abs(a - extension), std::abs(b - extension)) << c.name << " at cos " << cos_o;
            }
        }
    }
}

}  // namespace
