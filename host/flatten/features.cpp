#include "flatten/features.hpp"

#include "flatten/coverage.hpp"

#include "scene/vec_math.hpp"

#include <algorithm>
#include <cctype>

namespace vkrt {
namespace {

// Indexed by id.
constexpr std::array<const char*, kFeatureCount> kFeatureIds = [] {
    std::array<const char*, kFeatureCount> ids{};
#define FEATURE(id, name) ids[id] = #name;
#include "kernel/features.glsl"
#undef FEATURE
    return ids;
}();


// The order in which the logs list features: the kinds of primitive the scene holds
// (HAS_SPHERES, ...) first, then the others by id.
constexpr std::array<std::uint32_t, kFeatureCount> kDisplayOrder = [] {
    std::array<std::uint32_t, kFeatureCount> order{};
    std::array<bool, kFeatureCount> listed{};
    std::uint32_t n = 0;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    order[n++] = std::uint32_t(Feature::HAS_##NAMES);             \
    listed[std::uint32_t(Feature::HAS_##NAMES)] = true;
#include "kernel/shapes/kinds.glsl"
    for (std::uint32_t id = 0; id < kFeatureCount; ++id) {
        if (!listed[id]) order[n++] = id;
    }
    return order;
}();

}  // namespace

std::string feature_name(std::uint32_t id) {
    std::string name = kFeatureIds[id];
    if (name.rfind("HAS_", 0) == 0) {
        name.erase(0, 4);
    }
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return name;
}

std::vector<std::string> FeatureSet::kept() const {
    std::vector<std::string> names;
    for (std::uint32_t id : kDisplayOrder) {
        if (on_[id]) names.push_back(feature_name(id));
    }
    return names;
}

std::vector<std::string> FeatureSet::left_out() const {
    std::vector<std::string> names;
    for (std::uint32_t id : kDisplayOrder) {
        if (!on_[id]) names.push_back(feature_name(id));
    }
    return names;
}

FeatureSet analyze_features(const Scene& scene) {
    FeatureSet f;
    const bool has_lights = !scene.lights.empty();
    const bool has_geometry = scene.primitive_count() != 0;

    // Only materials that some primitive uses can ask for shading code.
    std::vector<bool> used(scene.materials.size(), false);
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    for (const Name& primitive : scene.names) used[primitive.material] = true;
#include "kernel/shapes/kinds.glsl"
    bool specular = false;
    bool emission = false;
    bool reflection = false;
    bool refraction = false;
    bool absorption = false;
    bool coat = false;
    bool sheen = false;
    bool rough_glass = false;
    bool dielectric_specular = false;
    bool microfacet = false;
    bool textures = false;
    // Only triangles and quads have the texture coordinates a normal map needs; a
    // coat's own map bends only a coat, which global mode alone renders.
    bool normal_maps = false;
    for (const auto& t : scene.triangles) {
        const Material& m = scene.materials[t.material];
        const bool coat_map = m.clearcoat_normal_map && m.metallic_roughness && m.metallic_roughness->clearcoat > 0.0 &&
                              scene.render.mode == RenderMode::Global;
        normal_maps = normal_maps || m.normal_map.has_value() || coat_map;
    }
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        if (!used[i]) continue;
        specular = specular || (m.ks > 0.0 && is_nonzero(m.specular));
        emission = emission || is_nonzero(m.emission);
        reflection = reflection || is_nonzero(m.reflect);
        refraction = refraction || is_nonzero(m.transmit) ||
                     (m.metallic_roughness && m.metallic_roughness->transmission > 0.0 &&
                      scene.render.mode == RenderMode::Global);
        microfacet = microfacet || m.metallic_roughness.has_value();
        coat = coat || (m.metallic_roughness && m.metallic_roughness->clearcoat > 0.0);
        sheen = sheen || (m.metallic_roughness && m.metallic_roughness->sheen_color != dvec3(0.0));
        dielectric_specular = dielectric_specular ||
                              (m.metallic_roughness && (m.metallic_roughness->has_specular() || m.specular_texture ||
                                                        m.specular_color_texture));
        // Rough where its GGX width passes the kernel's floor (kernel/lobes/glass.glsl);
        // a metallic texture can leave glass where the factor is 1.
        rough_glass = rough_glass ||
                      (m.metallic_roughness && m.metallic_roughness->transmission > 0.0 &&
                       (m.metallic_roughness->metallic < 1.0 || m.metallic_roughness_texture) &&
                       m.metallic_roughness->roughness * m.metallic_roughness->roughness > kernel::MIN_GGX_ALPHA);
        absorption = absorption || (m.metallic_roughness && m.metallic_roughness->absorbs() &&
                                    scene.render.mode == RenderMode::Global);
        textures = textures || m.textured();
    }

    f.set(Feature::HAS_SQUARES, scene.render.squares);
    f.set(Feature::HAS_PASSES, scene.render.passes);
    // A second mapping matters to the triangles whose material's textures read it.
    f.set(Feature::HAS_SECOND_MAPPING, std::any_of(scene.triangles.begin(), scene.triangles.end(), [&](const Triangle& t) {
              return used[t.material] && scene.materials[t.material].second_mapping.maps != 0u;
          }));
    f.set(Feature::HAS_VERTEX_COLORS, std::any_of(scene.triangles.begin(), scene.triangles.end(),
                                                  [](const Triangle& t) { return t.colors.has_value(); }));
    // Tangents only orient normal maps.
    f.set(Feature::HAS_TANGENTS, std::any_of(scene.triangles.begin(), scene.triangles.end(), [&](const Triangle& t) {
              return t.tangents.has_value() && scene.materials[t.material].normal_map.has_value();
          }));
    const std::vector<bool> tested = coverage_tested(scene);
    f.set(Feature::HAS_ALPHA, std::any_of(scene.triangles.begin(), scene.triangles.end(),
                                          [&](const Triangle& t) { return tested[t.material]; }));
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) f.set(Feature::HAS_##NAMES, !scene.names.empty());
#include "kernel/shapes/kinds.glsl"
    f.set(Feature::HAS_QUADS, std::any_of(scene.triangles.begin(), scene.triangles.end(),
                                          [](const Triangle& t) { return t.parallelogram; }));
    f.set(Feature::HAS_SMOOTH_NORMALS,
          std::any_of(scene.triangles.begin(), scene.triangles.end(),
                      [](const Triangle& t) { return t.normals.has_value(); }));
    const bool global = scene.render.mode == RenderMode::Global && has_geometry;
    // The emitter list is sampled in local mode with light samples to send, and in
    // global mode by next-event estimation (the path estimator's "nee").
    const bool area_lights =
        emission && (global ? scene.render.nee : scene.render.mode == RenderMode::Local && scene.render.light_samples > 0);
    // An environment image lights the scene through next-event estimation too.
    const bool environment_light = scene.environment.has_value() && global && scene.render.nee &&
                                   scene.render.estimator == Estimator::Path;
    const bool any_light = has_lights || area_lights || environment_light;

    f.set(Feature::HAS_GLOBAL, global);
    f.set(Feature::HAS_POINT_LIGHTS, has_lights && has_geometry);
    f.set(Feature::HAS_DIRECTED_LIGHTS,
          has_geometry && std::any_of(scene.lights.begin(), scene.lights.end(),
                                      [](const Light& l) { return l.type != LightType::Point; }));
    f.set(Feature::HAS_SHADOWS, scene.render.shadows && any_light && has_geometry);
    // The lift moves shadow rays' origins; without shadow rays it has nothing to move.
    f.set(Feature::HAS_TERMINATOR,
          f.has(Feature::HAS_SMOOTH_NORMALS) && f.has(Feature::HAS_SHADOWS) && scene.render.terminator);
    // In global mode the glossy lobe reflects whatever the paths bring, lights or not.
    f.set(Feature::HAS_SPECULAR, specular && (any_light || global));
    // Ambient light is local mode's stand-in for the indirect light global mode computes.
    f.set(Feature::HAS_AMBIENT, is_nonzero(scene.render.ambient) && has_geometry && !global);
    f.set(Feature::HAS_EMISSION, emission);
    f.set(Feature::HAS_JITTER, scene.render.jitter && !scene.render.corners);
    f.set(Feature::HAS_LENS, scene.camera.lens_radius > 0.0);
    // Glass reflects too: its reflection rays run under HAS_REFRACTION.
    const bool secondary = (global ? scene.render.max_bounces : scene.render.max_depth) > 0 && has_geometry;
    f.set(Feature::HAS_REFLECTION, secondary && reflection);
    f.set(Feature::HAS_REFRACTION, secondary && refraction);
    // Absorption happens inside glass, which only global mode's paths enter (refraction with it).
    f.set(Feature::HAS_ABSORPTION, secondary && refraction && absorption);
    f.set(Feature::HAS_ROUGH_GLASS, secondary && refraction && rough_glass && global);
    f.set(Feature::HAS_AREA_LIGHTS, area_lights);
    // Local mode shades a metallic-roughness material by its diffuse lobe (scene.hpp).
    f.set(Feature::HAS_MICROFACET, microfacet && global);
    f.set(Feature::HAS_COAT, coat && global);
    f.set(Feature::HAS_SHEEN, sheen && global);
    f.set(Feature::HAS_DIELECTRIC_SPECULAR, dielectric_specular && global);
    // Only triangles and quads carry texture coordinates.
    f.set(Feature::HAS_TEXTURES, textures && !scene.triangles.empty());
    f.set(Feature::HAS_ENVIRONMENT_MAP, scene.environment.has_value());
    f.set(Feature::HAS_NORMAL_MAPS, normal_maps);
    return f;
}

}  // namespace vkrt
