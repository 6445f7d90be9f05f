// The JSON scene format (docs/scene-format.md): reads a file into a validated
// Scene. Everything that could later crash, hang or silently render black is
// refused here with a message naming the file and the JSON path.
#include "scene/json_scene_loader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include "scene/estimator_spec.hpp"
#include "scene/generators.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/instance_object.hpp"
#include "scene/json_reader.hpp"
#include "scene/limits.hpp"
#include "scene/material_lookup.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"
#include "scene/shapes/shape_reader.hpp"
#include "scene/vec_math.hpp"

namespace vkrt {
namespace {

using json::Node;

bool parallel_or_zero(const dvec3& a, const dvec3& b) { return vkrt::parallel_or_zero(a, b, kParallelSine); }

std::uint32_t whole32(const Node& n, std::uint64_t lo, std::uint64_t hi) {
    return static_cast<std::uint32_t>(n.whole(lo, hi));
}

Camera read_camera(const Node& n) {
    n.allow_only({"eye", "look_at", "up", "fov", "width", "height", "lens_radius", "focus_distance"});
    Camera c;
    c.eye = n.required("eye").vec3();
    c.look_at = n.required("look_at").vec3();
    if (auto up = n.find("up")) c.up = up->vec3();
    if (auto fov = n.find("fov")) c.fov = fov->number_between_exclusive(0.0, 180.0);
    if (auto w = n.find("width")) c.width = whole32(*w, 1, limits::kMaxImageSide);
    if (auto h = n.find("height")) c.height = whole32(*h, 1, limits::kMaxImageSide);
    if (auto r = n.find("lens_radius")) c.lens_radius = r->number_at_least(0.0);
    if (auto f = n.find("focus_distance")) c.focus_distance = f->number_above(0.0);

    if (const std::string problem = limits::image_size_problem(c.width, c.height); !problem.empty()) {
        n.fail(problem);
    }
    const dvec3 view = c.look_at - c.eye;
    if (!is_nonzero(view)) {
        n.fail_field("look_at", fmt::format("look_at must differ from eye (both are {})", json::format_vec3(c.eye)));
    }
    if (!is_nonzero(c.up)) {
        n.fail_field("up", fmt::format("expected a non-zero vector, got {}", json::format_vec3(c.up)));
    }
    if (parallel_or_zero(c.up, view)) {
        n.fail_field("up", fmt::format("{}up {} is parallel to the view direction look_at - eye = {}",
                                       n.find("up") ? "" : "the default ", json::format_vec3(c.up),
                                       json::format_vec3(view)));
    }
    return c;
}

// "grid": "auto" | "on" | "off" | "uniform" | {"resolution": [x, y, z]} (docs/grid.md).
GridSettings read_grid(const Node& n) {
    GridSettings g;
    if (n.is_string()) {
        const std::string mode = n.string();
        if (mode == "auto") g.mode = GridMode::Auto;
        else if (mode == "on") g.mode = GridMode::On;
        else if (mode == "off") g.mode = GridMode::Off;
        else if (mode == "uniform") g.mode = GridMode::Uniform;
        else n.fail(fmt::format("unknown grid mode {} (expected \"auto\", \"on\", \"off\", \"uniform\" or an "
                                "object with \"resolution\")", json::quote_user(mode)));
        return g;
    }
    if (!n.is_object()) {
        n.fail_expected("\"auto\", \"on\", \"off\", \"uniform\" or an object with \"resolution\"");
    }
    n.allow_only({"resolution"});
    g.mode = GridMode::On;
    const auto cells = n.required("resolution").elements(3, "an array of 3 whole numbers (cells per axis)");
    for (int a = 0; a < 3; ++a) g.resolution[a] = whole32(cells[a], 1, limits::kMaxGridAxisCells);
    return g;
}

// The fields of global mode; an error in local mode, where they would do nothing.
void read_global(const Node& n, RenderSettings& r) {
    for (const char* field : {"estimator", "hemisphere", "nee", "max_bounces"}) {
        if (auto v = n.find(field); v && r.mode != RenderMode::Global) {
            v->fail("only used in global mode (add \"mode\": \"global\")");
        }
    }
    if (auto v = n.find("estimator")) {
        const std::string e = v->string();
        if (e == "paper") r.estimator = Estimator::Paper;
        else if (e == "path") r.estimator = Estimator::Path;
        else v->fail(fmt::format("unknown estimator {} (expected \"paper\" or \"path\")", json::quote_user(e)));
    }
    // The paper draws its angles uniformly (its Fig. 13); path tracing defaults to
    // cosine-weighted directions, the best of the three for diffuse surfaces.
    r.hemisphere = r.estimator == Estimator::Paper ? Hemisphere::Angles : Hemisphere::Cosine;
    if (auto v = n.find("hemisphere")) {
        const std::string h = v->string();
        if (h == "angles") r.hemisphere = Hemisphere::Angles;
        else if (h == "uniform") r.hemisphere = Hemisphere::Uniform;
        else if (h == "cosine") r.hemisphere = Hemisphere::Cosine;
        else v->fail(fmt::format("unknown hemisphere {} (expected \"angles\", \"uniform\" or \"cosine\")",
                                 json::quote_user(h)));
    }
    if (auto v = n.find("nee")) {
        r.nee = v->boolean();
        if (r.estimator == Estimator::Paper && r.nee) {
            v->fail("the paper estimator has no next-event estimation (use \"estimator\": \"path\")");
        }
    }
    if (r.estimator == Estimator::Paper) r.nee = false;
    if (auto v = n.find("max_bounces")) r.max_bounces = whole32(*v, 0, limits::kMaxBounces);
    // Global illumination is a Monte Carlo estimate over the pixel too.
    if (r.mode == RenderMode::Global && !n.find("jitter")) r.jitter = true;
}

// render.background as an image: {"image": file, "intensity", "rotation", "up"}.
Environment read_environment(const Node& n, std::vector<std::string>& warnings) {
    n.allow_only({"image", "intensity", "rotation", "up"});
    const Node file = n.required("image");
    Environment env = load_environment(file.file_path(), fmt::format("{}: {}", n.file(), file.path()), warnings);
    if (auto v = n.find("intensity")) env.intensity = v->number_between(0.0, 1e6);
    if (auto v = n.find("rotation")) env.rotation = v->number();
    if (auto v = n.find("up")) {
        env.up = v->vec3();
        if (!is_nonzero(env.up)) v->fail(fmt::format("expected a non-zero vector, got {}", json::format_vec3(env.up)));
        env.up = glm::normalize(env.up);
    }
    return env;
}

RenderSettings read_render(const Node& n) {
    n.allow_only({"mode", "aa", "jitter", "shadows", "terminator", "max_depth", "min_weight", "corners", "ambient", "background",
                  "seed", "spp", "loop_budget", "grid", "light_samples", "estimator", "hemisphere", "nee",
                  "max_bounces", "sampler", "exposure", "tonemap"});
    RenderSettings r;
    if (auto mode = n.find("mode")) {
        const std::string m = mode->string();
        if (m == "local") r.mode = RenderMode::Local;
        else if (m == "global") r.mode = RenderMode::Global;
        else mode->fail(fmt::format("unknown mode {} (expected \"local\" or \"global\")", json::quote_user(m)));
    }
    read_global(n, r);
    if (auto aa = n.find("aa")) r.aa = whole32(*aa, 1, limits::kMaxAa);
    if (auto jitter = n.find("jitter")) r.jitter = jitter->boolean();
    if (auto v = n.find("sampler")) {
        const std::optional<Sampler> s = parse_sampler(v->string());
        if (!s) v->fail(fmt::format("unknown sampler {} (expected \"sobol\" or \"hash\")", json::quote_user(v->string())));
        r.sampler = *s;
    }
    if (auto v = n.find("exposure")) {
        r.display.exposure = v->number();
        if (!(std::abs(r.display.exposure) <= limits::kMaxExposureStops)) {
            v->fail(fmt::format("expected a number of stops from -{0} to {0}, got {1}", limits::kMaxExposureStops,
                                r.display.exposure));
        }
    }
    if (auto v = n.find("tonemap")) {
        const std::optional<Tonemap> t = parse_tonemap(v->string());
        if (!t) v->fail(fmt::format("unknown tone map {} (expected \"none\" or \"filmic\")", json::quote_user(v->string())));
        r.display.tonemap = *t;
    }
    if (auto shadows = n.find("shadows")) r.shadows = shadows->boolean();
    if (auto terminator = n.find("terminator")) r.terminator = terminator->boolean();
    if (auto depth = n.find("max_depth")) r.max_depth = whole32(*depth, 0, limits::kMaxDepth);
    if (auto weight = n.find("min_weight")) {
        r.min_weight = weight->number_at_least(0.0);
        if (r.min_weight > 1.0) weight->fail(fmt::format("expected a number from 0 to 1, got {}", r.min_weight));
    }
    if (auto corners = n.find("corners")) r.corners = corners->boolean();
    if (auto ambient = n.find("ambient")) r.ambient = ambient->color();
    if (auto background = n.find("background"); background && !background->is_object()) r.background = background->color();
    if (auto seed = n.find("seed")) r.seed = whole32(*seed, 0, std::numeric_limits<std::uint32_t>::max());
    if (auto spp = n.find("spp")) r.spp = whole32(*spp, 1, limits::kMaxSpp);
    if (auto budget = n.find("loop_budget")) r.loop_budget = whole32(*budget, 1, limits::kMaxLoopBudget);
    if (auto grid = n.find("grid")) r.grid = read_grid(*grid);
    if (auto samples = n.find("light_samples")) r.light_samples = whole32(*samples, 0, limits::kMaxLightSamples);
    return r;
}


// A material's texture fields (read_texture).
constexpr std::array<const char*, 11> kTextureFields = {
    "texture", "normal_map", "emission_texture", "transmission_texture", "clearcoat_texture",
    "clearcoat_roughness_texture", "sheen_color_texture", "sheen_roughness_texture", "clearcoat_normal_map",
    "specular_texture", "specular_color_texture"};
// Their slots (kernel::MAP_<slot>), in the same order.
constexpr std::array<std::uint32_t, 11> kTextureSlots = {
    kernel::MAP_COLOR,     kernel::MAP_NORMAL,     kernel::MAP_EMISSION,   kernel::MAP_TRANSMISSION,
    kernel::MAP_COAT,      kernel::MAP_COAT_ROUGH, kernel::MAP_SHEEN,      kernel::MAP_SHEEN_ROUGH,
    kernel::MAP_COAT_NORMAL, kernel::MAP_SPECULAR, kernel::MAP_SPECULAR_COLOR};

// The fields of glTF's metallic-roughness model (scene.hpp): base_color, metallic and
// roughness, glass by transmission and thin (absorbing by attenuation_color and
// _distance), a clear coat, sheen and the dielectric's specular layer, which replace
// the Phong fields rather than add to them (ior serves both). Any of them makes a
// material a metallic-roughness one (read_material), which this reads.
constexpr std::array<const char*, 13> kMetallicRoughnessFields = {
    "base_color", "metallic", "roughness", "transmission", "thin", "attenuation_color", "attenuation_distance",
    "clearcoat", "clearcoat_roughness", "sheen_color", "sheen_roughness", "specular_factor", "specular_color"};

Material::MetallicRoughness read_metallic_roughness(const Node& n) {
    for (const char* phong : {"diffuse", "kd", "specular", "ks", "shininess", "reflect", "transmit", "fresnel"}) {
        if (n.find(phong)) {
            n.fail_field(phong, "a metallic-roughness material (base_color, metallic, roughness, transmission) has no Phong fields; "
                                "give one model or the other");
        }
    }
    Material::MetallicRoughness pbr;
    if (auto v = n.find("base_color")) pbr.base_color = v->unit_color();
    if (auto v = n.find("metallic")) pbr.metallic = v->number_between(0.0, 1.0);
    if (auto v = n.find("roughness")) pbr.roughness = v->number_between(0.0, 1.0);
    if (auto v = n.find("transmission")) pbr.transmission = v->number_between(0.0, 1.0);
    if (auto v = n.find("thin")) {
        if (!n.find("transmission")) n.fail_field("thin", "a thin wall needs \"transmission\"");
        pbr.thin = v->boolean();
    }
    for (const char* volume : {"attenuation_color", "attenuation_distance"}) {
        if (n.find(volume) && (!n.find("transmission") || pbr.thin)) {
            n.fail_field(volume, "attenuation is inside a solid: it needs \"transmission\" and no \"thin\"");
        }
    }
    if (auto v = n.find("clearcoat")) pbr.clearcoat = v->number_between(0.0, 1.0);
    if (auto v = n.find("clearcoat_roughness")) {
        if (!n.find("clearcoat")) n.fail_field("clearcoat_roughness", "a clear coat's roughness needs \"clearcoat\"");
        pbr.clearcoat_roughness = v->number_between(0.0, 1.0);
    }
    if (auto v = n.find("sheen_color")) pbr.sheen_color = v->unit_color();
    if (auto v = n.find("sheen_roughness")) {
        if (!n.find("sheen_color")) n.fail_field("sheen_roughness", "a sheen's roughness needs \"sheen_color\"");
        pbr.sheen_roughness = v->number_between(0.0, 1.0);
    }
    if (auto v = n.find("specular_factor")) pbr.specular = v->number_between(0.0, 1.0);
    if (auto v = n.find("specular_color")) pbr.specular_color = v->color();
    if (auto v = n.find("attenuation_color")) pbr.attenuation_color = v->unit_color();
    if (auto v = n.find("attenuation_distance")) pbr.attenuation_distance = v->number_above(0.0);
    return pbr;
}

// A normal map in field `field`: a linear image of tangent-space normals, glTF's
// encoding (TextureImage::normal_scale), its x and y scaled by the field
// `scale_field`. The material's ("normal_map", "normal_scale") or its clear coat's
// ("clearcoat_normal_map", "clearcoat_normal_scale", which needs "clearcoat").
std::optional<std::uint32_t> read_normal_map(const Node& n, const char* field, const char* scale_field, Scene& scene) {
    auto scale_node = n.find(scale_field);
    auto file = n.find(field);
    if (!file) {
        if (scale_node) n.fail_field(scale_field, fmt::format("a normal scale needs a \"{}\"", field));
        return std::nullopt;
    }
    double scale = 1.0;
    if (scale_node) {
        scale = scale_node->number();
        if (!(std::abs(scale) <= 1e6)) scale_node->fail(fmt::format("expected a number from -1e6 to 1e6, got {}", scale));
    }
    const std::string element = fmt::format("{}: {}", n.file(), file->path());
    const std::uint32_t map = load_texture(scene, file->file_path(), Encoding::Linear, element);
    scene.textures[map].normal_scale = scale;
    return map;
}

// A texture transform's "offset", "rotation" (degrees) and "scale", as glTF's
// KHR_texture_transform.
std::array<double, 6> read_texture_transform(const Node& t) {
    double offset[2] = {0.0, 0.0}, scale[2] = {1.0, 1.0}, rotation = 0.0;
    for (const char* key : {"offset", "scale"}) {
        if (auto v = t.find(key)) {
            const std::vector<Node> pair = v->elements(2, "an array of 2 numbers");
            double* out = std::string_view(key) == "offset" ? offset : scale;
            out[0] = pair[0].number();
            out[1] = pair[1].number();
        }
    }
    if (auto v = t.find("rotation")) rotation = v->number() * (std::numbers::pi / 180.0);
    return texture_transform(offset[0], offset[1], rotation, scale[0], scale[1]);
}

// A material's "second_texture_transform": a transform, as "texture_transform", for
// the textures its "textures" names (fields of the material's, the colour texture
// aside), which then read the coordinates through it instead (Material::SecondMapping).
void read_second_mapping(const Node& n, Material& m) {
    auto t = n.find("second_texture_transform");
    if (!t) return;
    t->allow_only({"offset", "rotation", "scale", "textures"});
    auto names = t->find("textures");
    if (!names) t->fail("a second texture transform needs \"textures\": the fields of the textures that read it");
    for (const Node& name : names->elements()) {
        const std::string field = name.string();
        const auto slot = std::find(kTextureFields.begin(), kTextureFields.end(), field);
        if (slot == kTextureFields.end()) {
            name.fail(fmt::format("{} is not a texture field (expected one of {})", json::quote_user(field),
                                  fmt::join(kTextureFields.begin() + 1, kTextureFields.end(), ", ")));
        }
        if (slot == kTextureFields.begin()) {
            name.fail("the colour texture reads \"texture_transform\": a material's coverage needs it on the first");
        }
        if (!n.find(field)) name.fail(fmt::format("the material has no \"{}\"", field));
        m.second_mapping.maps |= 1u << kTextureSlots[static_cast<std::size_t>(slot - kTextureFields.begin())];
    }
    m.second_mapping.transform = read_texture_transform(*t);
}

// A material's colour texture: the image file (relative to the scene file) and the
// optional transform of its coordinates, as glTF's KHR_texture_transform (rotation
// in degrees here, like every angle of the format).
void read_texture(const Node& n, Material& m, Scene& scene) {
    if (auto t = n.find("texture_transform")) {
        if (std::none_of(kTextureFields.begin(), kTextureFields.end(), [&](const char* f) { return n.find(f).has_value(); })) {
            n.fail_field("texture_transform", "a texture transform needs a \"texture\", a \"normal_map\", an "
                                              "\"emission_texture\" or a layer's texture");
        }
        t->allow_only({"offset", "rotation", "scale"});
        m.uv_transform = read_texture_transform(*t);
    }
    read_second_mapping(n, m);
    if (auto file = n.find("texture")) {
        const std::string element = fmt::format("{}: {}", n.file(), file->path());
        m.texture = load_texture(scene, file->file_path(), Encoding::SrgbUnlessFloat, element);
    }
    m.normal_map = read_normal_map(n, "normal_map", "normal_scale", scene);
    if (n.find("clearcoat_normal_map") && !n.find("clearcoat")) {
        n.fail_field("clearcoat_normal_map", "a clear coat normal map needs \"clearcoat\"");
    }
    m.clearcoat_normal_map = read_normal_map(n, "clearcoat_normal_map", "clearcoat_normal_scale", scene);
    if (auto file = n.find("emission_texture")) {
        const std::string element = fmt::format("{}: {}", n.file(), file->path());
        m.emission_texture = load_texture(scene, file->file_path(), Encoding::SrgbUnlessFloat, element);
    }
    // The metallic-roughness layers' textures, each needing its factor.
    const struct {
        const char* field;
        const char* factor;
        const char* what;
        Encoding encoding;
        std::optional<std::uint32_t> Material::*slot;
    } layers[] = {
        {"transmission_texture", "transmission", "a transmission texture", Encoding::Linear, &Material::transmission_texture},
        {"clearcoat_texture", "clearcoat", "a clear coat texture", Encoding::Linear, &Material::clearcoat_texture},
        {"clearcoat_roughness_texture", "clearcoat", "a clear coat roughness texture", Encoding::Linear,
         &Material::clearcoat_roughness_texture},
        {"sheen_color_texture", "sheen_color", "a sheen colour texture", Encoding::SrgbUnlessFloat,
         &Material::sheen_color_texture},
        {"sheen_roughness_texture", "sheen_color", "a sheen roughness texture", Encoding::Linear,
         &Material::sheen_roughness_texture},
        {"specular_texture", "specular_factor", "a specular texture", Encoding::Linear, &Material::specular_texture},
        {"specular_color_texture", "specular_color", "a specular colour texture", Encoding::SrgbUnlessFloat,
         &Material::specular_color_texture},
    };
    for (const auto& layer : layers) {
        if (auto file = n.find(layer.field)) {
            if (!n.find(layer.factor)) n.fail_field(layer.field, fmt::format("{} needs \"{}\"", layer.what, layer.factor));
            const std::string element = fmt::format("{}: {}", n.file(), file->path());
            m.*layer.slot = load_texture(scene, file->file_path(), layer.encoding, element);
        }
    }
}

// A material's coverage (glTF's alphaMode): "alpha_mode" "opaque", "mask" or "blend",
// the opacity "alpha" and, for a mask, "alpha_cutoff" (scene.hpp).
void read_alpha(const Node& n, Material& m) {
    auto mode = n.find("alpha_mode");
    if (mode) {
        const std::string v = mode->string();
        if (v == "opaque") m.alpha_mode = AlphaMode::Opaque;
        else if (v == "mask") m.alpha_mode = AlphaMode::Mask;
        else if (v == "blend") m.alpha_mode = AlphaMode::Blend;
        else mode->fail(fmt::format("unknown alpha mode {} (expected \"opaque\", \"mask\" or \"blend\")", json::quote_user(v)));
    }
    if (auto v = n.find("alpha")) {
        if (m.alpha_mode == AlphaMode::Opaque) {
            n.fail_field("alpha", "an opacity needs \"alpha_mode\": \"mask\" or \"blend\" (an opaque material has none)");
        }
        m.alpha = v->number_between(0.0, 1.0);
    }
    if (auto v = n.find("alpha_cutoff")) {
        if (m.alpha_mode != AlphaMode::Mask) n.fail_field("alpha_cutoff", "an alpha cutoff needs \"alpha_mode\": \"mask\"");
        m.alpha_cutoff = v->number_between(0.0, 1.0);
    }
}

Material read_material(const std::string& name, const Node& n, Scene& scene) {
    std::vector<std::string_view> allowed = {"diffuse", "kd", "specular", "ks", "shininess", "reflect", "transmit",
                                             "ior", "fresnel", "emission", "texture_transform", "second_texture_transform", "normal_scale",
                                             "clearcoat_normal_scale", "alpha_mode", "alpha", "alpha_cutoff"};
    allowed.insert(allowed.end(), kMetallicRoughnessFields.begin(), kMetallicRoughnessFields.end());
    allowed.insert(allowed.end(), kTextureFields.begin(), kTextureFields.end());
    n.allow_only(allowed);
    Material m;
    m.name = name;
    read_texture(n, m, scene);
    read_alpha(n, m);
    if (auto v = n.find("emission")) m.emission = v->color();
    if (auto v = n.find("ior")) m.ior = v->number_above(0.0);
    // Any field of the metallic-roughness model makes the material one (and is then checked).
    for (const char* field : kMetallicRoughnessFields) {
        if (n.find(field)) {
            m.metallic_roughness = read_metallic_roughness(n);
            return m;
        }
    }
    if (auto v = n.find("diffuse")) m.diffuse = v->color();
    if (auto v = n.find("kd")) m.kd = v->number_at_least(0.0);
    if (auto v = n.find("specular")) m.specular = v->color();
    if (auto v = n.find("ks")) m.ks = v->number_at_least(0.0);
    if (auto v = n.find("shininess")) m.shininess = v->number_at_least(0.0);
    if (auto v = n.find("reflect")) m.reflect = v->color();
    if (auto v = n.find("transmit")) m.transmit = v->color();
    if (auto v = n.find("fresnel")) m.fresnel = v->boolean();
    return m;
}

// Material name -> index into Scene::materials (definition order).
using MaterialIndex = std::map<std::string, std::uint32_t, std::less<>>;

MaterialIndex read_materials(const Node& n, Scene& scene) {
    MaterialIndex index;
    for (const auto& [name, node] : n.members()) {
        Material m = read_material(name, node, scene);
        scene.materials.push_back(std::move(m));
        index.emplace(name, static_cast<std::uint32_t>(scene.materials.size() - 1));
    }
    return index;
}

// A spot or directional light's "direction": any non-zero length, made unit here.
dvec3 read_direction(const Node& light) {
    const Node direction = light.required("direction");
    const dvec3 d = direction.vec3();
    if (!is_nonzero(d)) direction.fail("expected a non-zero vector (the way the light travels), got [0, 0, 0]");
    return robust_normalize(d);
}

// A spot light's cone, in degrees in the file and radians in the scene:
// 0 <= inner_angle < outer_angle <= 90.
void read_cone(const Node& light, Light& out) {
    double outer = 45.0;
    if (auto v = light.find("outer_angle")) {
        outer = v->number();
        if (!(outer > 0.0 && outer <= 90.0)) {
            v->fail(fmt::format("expected an angle in degrees above 0 and at most 90, got {}", outer));
        }
    }
    double inner = 0.0;
    if (auto v = light.find("inner_angle")) {
        inner = v->number_at_least(0.0);
        if (!(inner < outer)) {
            v->fail(fmt::format("expected an angle in degrees below outer_angle ({}{}), got {}", outer,
                                light.find("outer_angle") ? "" : ", its default", inner));
        }
    }
    out.inner_angle = glm::radians(inner);
    out.outer_angle = glm::radians(outer);
}

void read_lights(const Node& n, std::vector<Light>& out) {
    for (const Node& light : n.elements()) {
        const Node type = light.required("type");
        const std::string t = type.string();
        // Area lights are objects, not entries here: say so rather than "unknown".
        if (t == "area") {
            type.fail("there is no \"area\" light type: an object whose material has a nonzero \"emission\" "
                      "is an area light");
        }
        Light l;
        if (t == "point") {
            light.allow_only({"type", "position", "color", "intensity"});
            l.position = light.required("position").vec3();
        } else if (t == "spot") {
            light.allow_only({"type", "position", "direction", "inner_angle", "outer_angle", "color", "intensity"});
            l.type = LightType::Spot;
            l.position = light.required("position").vec3();
            l.direction = read_direction(light);
            read_cone(light, l);
        } else if (t == "directional") {
            light.allow_only({"type", "direction", "color", "intensity"});
            l.type = LightType::Directional;
            l.direction = read_direction(light);
        } else {
            type.fail(fmt::format("unknown light type {} (expected one of: point, spot, directional)",
                                  json::quote_user(t)));
        }
        if (auto c = light.find("color")) l.color = c->color();
        if (auto i = light.find("intensity")) l.intensity = i->number_at_least(0.0);
        out.push_back(l);
    }
}

// `node` holds a material's name.
std::uint32_t material_named(const Node& node, const MaterialIndex& materials) {
    const std::string name = node.string();
    if (const auto it = materials.find(name); it != materials.end()) return it->second;
    std::string defined;
    std::size_t shown = 0;
    for (const auto& [known, index] : materials) {
        if (++shown > 20) {
            defined += ", ...";
            break;
        }
        defined += (defined.empty() ? "" : ", ") + known;
    }
    node.fail(fmt::format("unknown material {} ({})", json::quote_user(name),
                          materials.empty() ? std::string("no materials are defined") : "defined: " + defined));
}

std::uint32_t material_of(const Node& object, const MaterialIndex& materials) {
    return material_named(object.required("material"), materials);
}

// A quad is one parallelogram (quad, scene/shapes/triangle.hpp).
void read_quad(const Node& n, const MaterialIndex& materials, std::vector<Triangle>& out) {
    n.allow_only({"corner", "edge1", "edge2", "material", "type"});
    const dvec3 corner = n.required("corner").vec3();
    const dvec3 e1 = n.required("edge1").vec3();
    const Node edge2 = n.required("edge2");
    const dvec3 e2 = edge2.vec3();
    if (!is_nonzero(e1)) n.fail_field("edge1", "expected a non-zero vector, got [0, 0, 0]");
    if (!is_nonzero(e2)) edge2.fail("expected a non-zero vector, got [0, 0, 0]");
    if (parallel_or_zero(e1, e2)) edge2.fail("edge1 and edge2 are parallel, so the quad has zero area");
    out.push_back(quad(corner, e1, e2, material_of(n, materials)));
}

// {"type": "gltf", "file": F, "transform": T}: a glTF file's meshes, materials and
// lights, placed by T (docs/scene-format.md).
void read_gltf_object(const Node& n, Scene& scene) {
    n.allow_only({"type", "file", "transform"});
    const Node file = n.required("file");
    const std::filesystem::path path = file.file_path();
    const std::optional<Node> transform = n.find("transform");
    const Transform t = transform ? read_transform(*transform) : Transform{};
    try {
        add_gltf(path, {t}, scene);
    } catch (const SceneError& e) {
        file.fail(e.what());  // the glTF's own message after the scene's path to it
    }
}

// The object types besides the kinds of primitive, each read by its own function.
constexpr const char* kOtherObjects = "quad, mesh, gltf, instance, random_spheres, sphereflake, torus_knot";

void read_objects(const Node& n, const MaterialIndex& materials, Scene& scene) {
    const MaterialLookup lookup = [&materials](const Node& name) { return material_named(name, materials); };
    // Only triangles have the texture coordinates that coverage needs (kernel/alpha.glsl).
    const MaterialLookup opaque = [&materials, &scene](const Node& name) {
        const std::uint32_t i = material_named(name, materials);
        const Material& m = scene.materials[i];
        if (m.alpha_mode != AlphaMode::Opaque) {
            name.fail(fmt::format("material {} has \"alpha_mode\": \"{}\", which applies to triangles, quads and "
                                  "meshes only (they have texture coordinates); give this object an opaque material",
                                  json::quote_user(m.name), m.alpha_mode == AlphaMode::Mask ? "mask" : "blend"));
        }
        return i;
    };
    ShapeReader shapes{.material = lookup};
    ShapeReader solids{.material = opaque};
    for (const Node& object : n.elements()) {
        const Node type = object.required("type");
        const std::string t = type.string();
        // Each kind of primitive by its name (host/scene/shapes/<name>.cpp, read_shape).
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    if (t == #name) {                                                                    \
        read_shape(object, kernel::REF_##NAME == kernel::REF_TRIANGLE ? shapes : solids, scene.names); \
        continue;                                                                        \
    }
#include "kernel/shapes/kinds.glsl"
        if (t == "quad") {
            read_quad(object, materials, scene.triangles);
        } else if (t == "mesh") {
            read_mesh(object, lookup, scene);
        } else if (t == "random_spheres") {
            read_random_spheres(object, opaque, scene.spheres);
        } else if (t == "sphereflake") {
            read_sphereflake(object, opaque, scene.spheres);
        } else if (t == "torus_knot") {
            read_torus_knot(object, lookup, scene);
        } else if (t == "gltf") {
            read_gltf_object(object, scene);
        } else if (t == "instance") {
            read_instance(object, lookup, scene);
        } else {
            const std::vector<std::string> kinds{
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) #name,
#include "kernel/shapes/kinds.glsl"
            };
            type.fail(fmt::format("unknown object type {} (expected one of: {}, {})", json::quote_user(t),
                                  fmt::join(kinds, ", "), kOtherObjects));
        }
    }
    shapes.warn(n.file(), scene.warnings);
    solids.warn(n.file(), scene.warnings);
}

// Local mode and the paper's estimator have the paper's Phong model only: they shade
// a metallic-roughness material by its diffuse lobe (scene.hpp), which the user is
// told rather than left to find in the image.
void warn_paper_models(Scene& scene) {
    const bool paper = scene.render.mode == RenderMode::Local || scene.render.estimator == Estimator::Paper;
    if (!paper) return;
    std::vector<std::string> names;
    for (const Material& m : scene.materials) {
        if (m.metallic_roughness) names.push_back(json::quote_user(m.name));
    }
    if (names.empty()) return;
    scene.warnings.push_back(fmt::format(
        "{}: material{} {} shaded by the diffuse lobe alone: {} has the paper's Phong model only "
        "(the path estimator of render.mode \"global\" renders metallic and roughness)",
        scene.source.string(), names.size() == 1 ? "" : "s", fmt::join(names, ", "),
        scene.render.mode == RenderMode::Local ? "local mode" : "the paper estimator"));
}

}  // namespace

Scene load_json_scene(const std::filesystem::path& file) {
    return parse_json_scene(read_text(file, file.string(), "scene"), file);
}

Scene parse_json_scene(const std::string& text, const std::filesystem::path& file) {
    const std::string name = file.string();
    const json::Document doc = json::parse_document(name, text);
    const Node root(name, doc);
    if (!root.is_object()) root.fail(fmt::format("expected a JSON object at the top level, got {}", root.describe()));
    root.allow_only({"camera", "render", "materials", "lights", "objects"});

    Scene scene;
    scene.source = file;
    scene.camera = read_camera(root.required("camera"));
    if (auto render = root.find("render")) {
        scene.render = read_render(*render);
        if (auto b = render->find("background"); b && b->is_object()) scene.environment = read_environment(*b, scene.warnings);
        const std::string problem =
            limits::image_size_problem(scene.camera.width, scene.camera.height, scene.render.corners);
        if (!problem.empty()) render->fail_field("corners", problem);
    }
    const MaterialIndex materials = read_materials(root.required("materials"), scene);
    if (auto lights = root.find("lights")) read_lights(*lights, scene.lights);
    read_objects(root.required("objects"), materials, scene);
    warn_paper_models(scene);
    return scene;
}

}  // namespace vkrt
