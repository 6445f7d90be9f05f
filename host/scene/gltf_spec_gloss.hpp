#pragma once
// KHR_materials_pbrSpecularGlossiness (archived, Khronos) as vkrt's
// metallic-roughness material, by the extension's own reference conversion
// (its examples, "convert-between-workflows"; decision 0033). The extension's BRDF
// inputs are a diffuse colour c_diff = diffuse (1 - max(specular)), a reflectance
// F0 = specular at normal incidence and alpha = (1 - glossiness)^2; the conversion
// picks the base colour and metallic factor whose F0 (mix(0.04, base, metallic))
// and diffuse colour (0.96 (1 - metallic) base) in glTF's reference model are
// those, measured by perceived brightness, and roughness = 1 - glossiness, as
// Blender's importer takes it.
#include <string>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "scene/scene.hpp"

namespace tinygltf {
class Value;
}

namespace vkrt::gltf {

struct SpecularGlossiness {
    glm::dvec3 diffuse{1.0};   // linear, 0 to 1
    glm::dvec3 specular{1.0};  // linear, 0 to 1
    double glossiness = 1.0;   // 0 (rough) to 1 (smooth)
};

// The conversion, pure, over linear values: the factors', or one texel's (a
// texture's value times its factor).
Material::MetallicRoughness to_metallic_roughness(const SpecularGlossiness& sg);

// One texel of the extension's textures as the material's values there: the
// diffuse texture's colour and the specular-glossiness texture's colour (both
// sRGB-decoded to linear) and glossiness (its alpha, linear), each times its factor,
// converted as above. Textures that are absent are given as 1.
Material::MetallicRoughness convert_texel(glm::dvec3 diffuse, glm::dvec4 specular_glossiness,
                                          const SpecularGlossiness& factors);

// The factors of a material's extension object (defaults where absent), each
// checked: throws SceneError naming `file` and the member under `element`. The
// diffuse factor's alpha is returned in `alpha`.
SpecularGlossiness read_specular_glossiness(const tinygltf::Value& extension, const std::string& element,
                                            const std::string& file, double& alpha);

}  // namespace vkrt::gltf
