#include "scene/gltf_spec_gloss.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <tiny_gltf.h>

#include "scene/scene_error.hpp"

namespace vkrt::gltf {
namespace {

constexpr double kDielectricF0 = 0.04;  // a metallic-roughness dielectric's reflectance
constexpr double kEpsilon = 1e-6;

// A colour's perceived brightness, as the extension's reference conversion weighs
// it: sqrt(0.299 r^2 + 0.587 g^2 + 0.114 b^2).
double perceived(glm::dvec3 c) { return std::sqrt(0.299 * c.r * c.r + 0.587 * c.g * c.g + 0.114 * c.b * c.b); }

double max_component(glm::dvec3 c) { return std::max({c.r, c.g, c.b}); }

// `n` numbers from 0 to 1 of a member, or none when it is absent.
std::vector<double> unit_numbers(const tinygltf::Value& object, const char* key, std::size_t n,
                                 const std::string& element, const std::string& file) {
    if (!object.Has(key)) return {};
    const tinygltf::Value& v = object.Get(key);
    const auto fail = [&] {
        throw SceneError(fmt::format("{}: {}.{}: expected {} number{} from 0 to 1", file, element, key, n,
                                     n == 1 ? "" : "s"));
    };
    std::vector<double> out;
    if (n == 1) {
        if (!v.IsNumber()) fail();
        out.push_back(v.GetNumberAsDouble());
    } else {
        if (!v.IsArray() || v.ArrayLen() != n) fail();
        for (std::size_t i = 0; i < n; ++i) {
            if (!v.Get(static_cast<int>(i)).IsNumber()) fail();
            out.push_back(v.Get(static_cast<int>(i)).GetNumberAsDouble());
        }
    }
    for (double x : out) {
        if (!(x >= 0.0 && x <= 1.0)) fail();
    }
    return out;
}

}  // namespace

Material::MetallicRoughness to_metallic_roughness(const SpecularGlossiness& sg) {
    // The BRDF inputs the extension defines, by perceived brightness.
    const double one_minus_specular = 1.0 - max_component(sg.specular);
    const double diffuse = perceived(sg.diffuse) * one_minus_specular, f0 = perceived(sg.specular);
    // The metallic factor m of the metallic-roughness material whose F0 and diffuse
    // colour, in glTF's reference model, are those: 0.04 (1 - m) + b m = f0 and
    // 0.96 (1 - m) b = diffuse give 0.04 m^2 + (diffuse / 0.96 + f0 - 0.08) m + 0.04 - f0 = 0.
    // Below a dielectric's reflectance the material is a dielectric.
    double metallic = 0.0;
    if (f0 >= kDielectricF0) {
        const double a = kDielectricF0;
        const double b = diffuse / (1.0 - kDielectricF0) + f0 - 2.0 * kDielectricF0;
        const double c = kDielectricF0 - f0;
        metallic = std::clamp((-b + std::sqrt(std::max(b * b - 4.0 * a * c, 0.0))) / (2.0 * a), 0.0, 1.0);
    }
    // The base colour, per channel, from the diffuse colour where the material is
    // a dielectric and from the specular colour where it is a metal; blended by m^2.
    const glm::dvec3 from_diffuse =
        sg.diffuse * (one_minus_specular / (1.0 - kDielectricF0) / std::max(1.0 - metallic, kEpsilon));
    const glm::dvec3 from_specular = (sg.specular - kDielectricF0 * (1.0 - metallic)) / std::max(metallic, kEpsilon);
    Material::MetallicRoughness mr;
    mr.base_color = glm::clamp(glm::mix(from_diffuse, from_specular, metallic * metallic), 0.0, 1.0);
    mr.metallic = metallic;
    mr.roughness = 1.0 - sg.glossiness;
    return mr;
}

Material::MetallicRoughness convert_texel(glm::dvec3 diffuse, glm::dvec4 specular_glossiness,
                                          const SpecularGlossiness& factors) {
    return to_metallic_roughness({diffuse * factors.diffuse, glm::dvec3(specular_glossiness) * factors.specular,
                                  specular_glossiness.a * factors.glossiness});
}

SpecularGlossiness read_specular_glossiness(const tinygltf::Value& extension, const std::string& element,
                                            const std::string& file, double& alpha) {
    if (!extension.IsObject()) throw SceneError(fmt::format("{}: {}: expected an object", file, element));
    SpecularGlossiness sg;
    alpha = 1.0;
    if (const std::vector<double> d = unit_numbers(extension, "diffuseFactor", 4, element, file); !d.empty()) {
        sg.diffuse = glm::dvec3(d[0], d[1], d[2]);
        alpha = d[3];
    }
    if (const std::vector<double> s = unit_numbers(extension, "specularFactor", 3, element, file); !s.empty()) {
        sg.specular = glm::dvec3(s[0], s[1], s[2]);
    }
    if (const std::vector<double> g = unit_numbers(extension, "glossinessFactor", 1, element, file); !g.empty()) {
        sg.glossiness = g[0];
    }
    return sg;
}

}  // namespace vkrt::gltf
