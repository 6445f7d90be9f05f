#include "flatten/flat_scene.hpp"

#include "flatten/coverage.hpp"
#include "flatten/emission_footprint.hpp"
#include "flatten/environment_table.hpp"
#include "flatten/ggx_albedo.hpp"
#include "flatten/rough_glass_albedo.hpp"
#include "flatten/sheen_albedo.hpp"
#include "scene/shapes/support.hpp"
#include "scene/texture_image.hpp"
#include "scene/vec_math.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <limits>
#include <numeric>
#include <cmath>
#include <span>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/packing.hpp>
#include <glm/trigonometric.hpp>

namespace vkrt {
namespace {

using kernel::uvec3;
using kernel::uvec4;
using kernel::vec3;
using kernel::vec4;

// Where the kernel's coordinates start, in the scene's: the camera's eye rounded to a
// multiple of 64 on each axis. Every position the kernel gets is the scene's minus
// this, subtracted in double and only then rounded to float. A float coordinate is
// only known to 2^-24 of its magnitude, so what decides precision is then the
// distance from the camera, not from the scene's origin: a scene at 1e6, where
// float's step is 0.0625, renders as it does near the origin.
//
// Why not the eye itself. Rounded to 64, the eye lies within 32 of the kernel's origin
// on each axis, so an eye ray's hit point eye + t dir near a kernel coordinate of 0
// errs by a few ULPs of 32, 2^-18, inside the 2^-16 by which ray.glsl moves such
// points off their surface; elsewhere the point is exact to ULPs of its own
// coordinates, which its 256-ULP offset covers. And every scene whose eye lies within
// 32 of its origin (each one under scenes/, each test's) keeps its coordinates bit for
// bit.
// With the eye itself, the shipped scenes' coordinates grow to the camera's distance
// (about 5), their offsets with them, and in scenes/gallery/c_light_in_cylinder.json
// the 256-ULP offset (1.2e-4) then exceeded the 1e-4 of a 0.6-long shadow ray that
// visibility.glsl leaves short of an area light's point: the ray reached the lamp's own
// surface and the lit tube went dark on 9% of pixels. A translation by a multiple of
// 64 gives the kernel the same numbers.
dvec3 kernel_origin(const dvec3& eye) {
    constexpr double kStep = 64.0;  // a power of two: eye / kStep and back are exact
    return glm::round(eye / kStep) * kStep;
}

// The camera frame is built in double and rounded once, so the kernel's rays do not
// inherit the error of a float cross product and tan().
void set_camera(const Camera& cam, bool corners, const dvec3& origin, kernel::Params& p) {
    const dvec3 forward = robust_normalize(cam.look_at - cam.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, robust_normalize(cam.up)));
    const dvec3 up = glm::cross(right, forward);
    const double pixel = 2.0 * std::tan(glm::radians(cam.fov) / 2.0) / cam.height;
    const dvec3 step_right = right * pixel;
    const dvec3 step_down = -up * pixel;
    dvec3 corner = forward - step_right * (cam.width / 2.0) - step_down * (cam.height / 2.0);
    // Ray (x, y) of the corner grid goes through corner (x - 0.5, y - 0.5) + the
    // sample's offset of 0.5: the image's pixel corner (x, y).
    if (corners) corner -= (step_right + step_down) * 0.5;
    kernel::set_camera_eye(p, vec3(cam.eye - origin));
    kernel::set_camera_corner(p, vec3(corner));
    kernel::set_camera_right(p, vec3(step_right));
    kernel::set_camera_down(p, vec3(step_down));
    kernel::set_lens_scale(p, static_cast<float>(cam.lens_radius / pixel));
    kernel::set_focus_distance(p, static_cast<float>(cam.focus_distance.value_or(glm::length(cam.look_at - cam.eye))));
}

// The texture fields every material carries: the textures (0: none), the
// coordinates' transform, and the metallic-roughness factors that texture.glsl
// rebuilds a textured metallic-roughness material from.
void set_texture_fields(const Material& m, kernel::Material& out) {
    const auto& a = m.uv_transform;
    const auto map = [](const std::optional<std::uint32_t>& t) { return t ? *t + 1u : 0u; };
    out.color_map = map(m.texture);
    out.metal_rough_map = map(m.metallic_roughness_texture);
    out.normal_map = map(m.normal_map);
    out.emission_map = map(m.emission_texture);
    out.transmission_map = map(m.transmission_texture);
    out.coat_map = map(m.clearcoat_texture);
    out.coat_rough_map = map(m.clearcoat_roughness_texture);
    out.sheen_map = map(m.sheen_color_texture);
    out.sheen_rough_map = map(m.sheen_roughness_texture);
    out.coat_normal_map = map(m.clearcoat_normal_map);
    out.specular_map = map(m.specular_texture);
    out.specular_color_map = map(m.specular_color_texture);
    out.uv_u = vec3(float(a[0]), float(a[1]), float(a[2]));
    out.uv_v = vec3(float(a[3]), float(a[4]), float(a[5]));
    const auto& b = m.second_mapping.transform;
    out.second_maps = m.second_mapping.maps;
    out.second_coords = m.second_mapping.own_coordinates ? 1u : 0u;
    out.uv2_u = vec3(float(b[0]), float(b[1]), float(b[2]));
    out.uv2_v = vec3(float(b[3]), float(b[4]), float(b[5]));
}

kernel::Material flatten(const Material& m) {
    kernel::Material out{};
    out.shininess = float(m.shininess);
    out.ior = float(m.ior);
    out.emission = vec3(m.emission);
    if (const auto& pbr = m.metallic_roughness) {
        // glTF 2.0 appendix B: dielectrics reflect ((ior - 1) / (ior + 1))^2 at normal
        // incidence (4% at ior 1.5), metals their base colour; metals have no diffuse
        // lobe. Glass takes transmission (1 - metallic) of the material and the metal
        // keeps its share of the whole, as kernel/texture.glsl's
        // set_metallic_roughness rebuilds a textured material. Fresnel splits any
        // mirror or glass of such a material.
        const double f0 = std::pow((m.ior - 1.0) / (m.ior + 1.0), 2.0);
        const double glass = pbr->transmission * (1.0 - pbr->metallic);
        const double metal = glass > 0.0 ? (glass < 1.0 ? pbr->metallic / (1.0 - glass) : 0.0) : pbr->metallic;
        out.diffuse = vec3((1.0 - metal) * pbr->base_color);
        out.kd = 1.0f;
        out.fresnel = 1u;
        // KHR_materials_specular's dielectric: the ior's f0 when it is absent.
        const dvec3 dielectric = glm::min(dvec3(f0) * pbr->specular_color, dvec3(1.0)) * pbr->specular;
        out.ggx_f0 = vec3(glm::mix(dielectric, pbr->base_color, metal));
        out.ggx_f90 = float(glm::mix(pbr->specular, 1.0, metal));
        out.dielectric_f0_rgb = vec3(dielectric);
        out.dielectric_f90 = float(pbr->specular);
        out.specular_color = vec3(pbr->specular_color);
        out.ggx_alpha = float(std::max(pbr->roughness * pbr->roughness, double(kernel::MIN_GGX_ALPHA)));
        out.base_color = vec3(pbr->base_color);
        out.metallic = float(pbr->metallic);
        out.roughness = float(pbr->roughness);
        out.transmission = float(pbr->transmission);
        out.transmit = vec3(glass * pbr->base_color);
        out.dielectric_f0 = float(f0);
        out.thin_walled = pbr->thin ? 1u : 0u;
        if (pbr->sheen_color != dvec3(0.0)) {
            out.sheen_color = vec3(pbr->sheen_color);
            out.sheen_alpha = float(std::max(pbr->sheen_roughness * pbr->sheen_roughness,
                                             double(kernel::MIN_SHEEN_ALPHA)));
        }
        if (pbr->clearcoat > 0.0) {
            out.coat = float(pbr->clearcoat);
            out.coat_alpha = float(std::max(pbr->clearcoat_roughness * pbr->clearcoat_roughness,
                                            double(kernel::MIN_GGX_ALPHA)));
        }
        if (pbr->absorbs()) {
            // sigma = -ln(colour) / distance, at most the largest float: a black channel
            // absorbs all of any positive distance and none of zero.
            for (int c = 0; c < 3; ++c) {
                const double sigma = -std::log(pbr->attenuation_color[c]) / pbr->attenuation_distance;
                out.attenuation[c] = float(std::min(sigma, double(std::numeric_limits<float>::max())));
            }
        }
    } else {
        out.diffuse = vec3(m.diffuse);
        out.kd = float(m.kd);
        out.specular = vec3(m.specular);
        out.ks = float(m.ks);
        out.mirror = vec3(m.reflect);
        out.transmit = vec3(m.transmit);
        out.fresnel = m.fresnel ? 1u : 0u;
    }
    set_texture_fields(m, out);
    out.alpha_mode = std::uint32_t(m.alpha_mode);
    out.alpha = float(m.alpha);
    out.alpha_cutoff = float(m.alpha_cutoff);
    return out;
}

// Marks the triangles whose material's coverage the kernel tests (coverage.hpp).
void mark_coverage_tested(const Scene& scene, FlatScene& g) {
    const std::vector<bool> tested = coverage_tested(scene);
    for (std::size_t i = 0; i < g.triangles.size(); ++i) {
        if (tested[scene.triangles[i].material]) g.triangles[i].meta.y |= kernel::TRIANGLE_ALPHA_TESTED;
    }
}

static_assert(std::uint32_t(Wrap::Repeat) == kernel::WRAP_REPEAT && std::uint32_t(Wrap::Clamp) == kernel::WRAP_CLAMP &&
              std::uint32_t(Wrap::Mirror) == kernel::WRAP_MIRROR);
static_assert(std::uint32_t(TexelFormat::Half) == kernel::TEXEL_HALF &&
              std::uint32_t(TexelFormat::Rgba8) == kernel::TEXEL_RGBA8);

// The textures' records (kernel::Texture) over the scene's own texels, shared, and
// the sRGB table at the start of table_words where a texture is sRGB-encoded.
void add_textures(const Scene& scene, FlatScene& g) {
    bool srgb = false;
    for (const TextureImage& t : scene.textures) {
        std::uint32_t flags = std::uint32_t(t.wrap_s) | (std::uint32_t(t.wrap_t) << 2u) | (std::uint32_t(t.format) << 4u);
        if (t.srgb) flags |= kernel::TEXTURE_SRGB_BIT;
        srgb = srgb || t.srgb;
        g.textures.push_back(kernel::Texture(uvec4(std::uint32_t(t.first_word), t.width, t.height, flags),
                                             vec4(float(t.normal_scale), 0.0f, 0.0f, 0.0f)));
    }
    g.texture_words = SharedArray<std::uint32_t>(scene.texels.share());
    if (srgb) {
        for (float v : srgb_byte_table()) g.table_words.push_back(std::bit_cast<std::uint32_t>(v));
    }
}

// The environment's words after the sRGB table, and the chance that next-event
// estimation draws from it rather than from the emitters: where the path estimator
// samples lights at all, one half beside emitters (their powers and the image's do
// not compare: one is at a distance, the other not), else all.
void add_environment(const Scene& scene, FlatScene& g) {
    bool sampled = false;
    kernel::set_environment_first_word(g.params, append_environment(*scene.environment, g.table_words, sampled));
    const RenderSettings& r = scene.render;
    const bool nee = g.features.has(Feature::HAS_GLOBAL) && r.estimator == Estimator::Path && r.nee;
    const float choice = !(nee && sampled) ? 0.0f : g.features.has(Feature::HAS_AREA_LIGHTS) ? 0.5f : 1.0f;
    kernel::set_environment_choice(g.params, choice);
}

// Whether a material's glass may carry a specular layer (kernel/lobes/glass.glsl
// glass_lobe's `layered`, or a specular texture that makes it so per hit).
bool has_layered_glass(const FlatScene& g) {
    return std::ranges::any_of(g.materials, [](const kernel::Material& m) {
        return m.transmission > 0.0f && (m.dielectric_f90 != 1.0f || m.dielectric_f0_rgb != vec3(m.dielectric_f0) ||
                                         m.specular_map != 0u || m.specular_color_map != 0u);
    });
}

// The rough lobe's albedo tables, which its multiple-scattering lobe reads
// (kernel/lobes/ggx_multiple.glsl), after what table_words holds already, and with
// HAS_SHEEN the sheen's right after them (kernel/lobes/sheen.glsl), then with
// HAS_ROUGH_GLASS rough glass's (kernel/lobes/rough_glass.glsl), and those of its
// specular layer where glass has one.
void add_ggx_tables(FlatScene& g) {
    const std::vector<std::uint32_t>& table = ggx_albedo_table();
    kernel::set_ggx_table_first_word(g.params, static_cast<std::uint32_t>(g.table_words.size()));
    g.table_words.insert(g.table_words.end(), table.begin(), table.end());
    if (g.features.has(Feature::HAS_SHEEN)) {
        const std::vector<std::uint32_t>& sheen = sheen_albedo_table();
        g.table_words.insert(g.table_words.end(), sheen.begin(), sheen.end());
    }
    if (g.features.has(Feature::HAS_ROUGH_GLASS)) {
        const std::vector<std::uint32_t>& glass = rough_glass_albedo_table();
        g.table_words.insert(g.table_words.end(), glass.begin(), glass.end());
        if (g.features.has(Feature::HAS_DIELECTRIC_SPECULAR) && has_layered_glass(g)) {
            const std::vector<std::uint32_t>& layer = rough_glass_layer_tables();
            g.table_words.insert(g.table_words.end(), layer.begin(), layer.end());
        }
    }
}

// Per triangle, six words of table_words (kernel/vertex_data.glsl): the half floats
// (x, y), (z, w) of each corner of `corners(t)`, zeros for a triangle without them,
// which the kernel never reads. Returns where they start.
template <class Corners>
std::uint32_t add_corner_words(const Scene& scene, Corners corners, FlatScene& g) {
    const auto first = static_cast<std::uint32_t>(g.table_words.size());
    g.table_words.reserve(g.table_words.size() + 6 * scene.triangles.size());
    for (const Triangle& t : scene.triangles) {
        const auto& given = corners(t);
        for (int k = 0; k < 3; ++k) {
            const glm::vec4 c = given ? (*given)[k] : glm::vec4(0.0f);
            g.table_words.push_back(glm::packHalf2x16(glm::vec2(c.x, c.y)));
            g.table_words.push_back(glm::packHalf2x16(glm::vec2(c.z, c.w)));
        }
    }
    return first;
}

// The triangles' second texture coordinates (kernel/vertex_data.glsl, second_uv): the
// float bits of u and v of each corner, a triangle's first coordinates where it has
// no second ones. Returns where they start.
std::uint32_t add_second_uv_words(const Scene& scene, FlatScene& g) {
    const auto first = static_cast<std::uint32_t>(g.table_words.size());
    g.table_words.reserve(g.table_words.size() + 6 * scene.triangles.size());
    for (const Triangle& t : scene.triangles) {
        for (const glm::dvec2& c : t.second_uvs ? *t.second_uvs : texture_corners(t)) {
            g.table_words.push_back(std::bit_cast<std::uint32_t>(static_cast<float>(c.x)));
            g.table_words.push_back(std::bit_cast<std::uint32_t>(static_cast<float>(c.y)));
        }
    }
    return first;
}

// A light as the kernel reads it (kernel/layout.glsl, Light): a directional light as
// the point at infinity toward it (w = 0), which no origin moves; a spot light's
// axis and cone angles folded into the cone's linear ramp in the cosine, with the
// width floored at 0.001 as glTF's reference code floors it (a ramp of 0 would
// divide by 0).
kernel::Light flatten(const Light& l, const dvec3& origin) {
    const vec4 radiance = to_vec4(l.color * l.intensity);
    switch (l.type) {
    case LightType::Directional:
        return kernel::Light(to_vec4(-l.direction, 0.0), radiance, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    case LightType::Spot: {
        const double cos_outer = std::cos(l.outer_angle);
        const double scale = 1.0 / std::max(std::cos(l.inner_angle) - cos_outer, 1e-3);
        return kernel::Light(to_vec4(l.position - origin, 1.0), radiance, to_vec4(l.direction * scale, -cos_outer * scale));
    }
    case LightType::Point: break;
    }
    return kernel::Light(to_vec4(l.position - origin, 1.0), radiance, vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

double mean(const dvec3& c) { return (c.x + c.y + c.z) / 3.0; }

// The emissive primitives as area lights (kernel/emitters.glsl): one Emitter each,
// with the running fractions of the total power (area times mean emitted radiance)
// up to it and before it, by which the kernel picks one with probability
// proportional to its power and reuses the number that picked it. A triangle with an
// emission texture counts by the mean emission over its footprint, which its record
// carries for the kernel (emission_footprint.hpp); an emitter of no power (a black
// footprint) is left out.
void add_emitters(const Scene& scene, FlatScene& g) {
    struct Found {
        std::uint32_t ref;
        double power;            // area * mean radiance
        std::uint32_t part = 0;  // Emitter.prim.y: of a cylinder, kernel::CYLINDER_SIDE, _BASE_CAP, _TOP_CAP
    };
    std::vector<Found> found;
    auto add = [&](std::uint32_t kind, std::size_t i, double area, std::uint32_t material, std::uint32_t part = 0) {
        const double weight = mean(scene.materials[material].emission);
        if (weight > 0.0) found.push_back({(kind << kernel::REF_KIND_SHIFT) | std::uint32_t(i), area * weight, part});
    };
    EmissionFootprints footprints(scene);
    const bool textured = g.features.has(Feature::HAS_TEXTURES);
    // A triangle with an emission texture weighs by its footprint, which its record
    // carries for the kernel; an emitter of no power (a black footprint) is left out.
    auto add_textured = [&](std::size_t i) {
        const Triangle& t = scene.triangles[i];
        const Material& m = scene.materials[t.material];
        if (!is_nonzero(m.emission)) return;
        // The emission texture's own mapping (kernel/texture.glsl).
        const bool second = g.features.has(Feature::HAS_SECOND_MAPPING) && m.on_second_mapping(kernel::MAP_EMISSION);
        const std::array<glm::dvec2, 3> uv =
            second && m.second_mapping.own_coordinates && t.second_uvs ? *t.second_uvs : texture_corners(t);
        const std::array<glm::dvec2, 4> corners{uv[0], uv[1], uv[2], uv[0] + uv[2] - uv[1]};
        const double weight = footprints.mean_emission(m, std::span(corners).first(t.parallelogram ? 4 : 3),
                                                       second ? m.second_mapping.transform : m.uv_transform);
        // The kernel reads the weight in float: one that would round to 0 is the
        // smallest normal float instead, so that an emitting footprint stays an emitter.
        const float bits = weight > 0.0 ? std::max(float(weight), std::numeric_limits<float>::min()) : 0.0f;
        g.triangles[i].meta.w = std::bit_cast<std::uint32_t>(bits);
        if (bits > 0.0f) {
            found.push_back({(kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | std::uint32_t(i),
                             emitter_area(t, 0) * bits, 0});
        }
    };
    // Kind by kind, in the kernel's order, each primitive's parts in order (a
    // cylinder's side, then its caps: each picked by its own power and sampled by its
    // own parameterization).
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)                                         \
    for (std::size_t i = 0; i < scene.names.size(); ++i) {                                                  \
        const Name& primitive = scene.names[i];                                                             \
        if (kernel::REF_##NAME == kernel::REF_TRIANGLE && textured &&                                       \
            scene.materials[primitive.material].emission_texture) {                                         \
            add_textured(i);                                                                                \
            continue;                                                                                       \
        }                                                                                                   \
        for (std::uint32_t part = 0; part < emitter_parts(primitive); ++part) {                             \
            add(kernel::REF_##NAME, i, emitter_area(primitive, part), primitive.material, part);           \
        }                                                                                                   \
    }
#include "kernel/shapes/kinds.glsl"
    double total = 0.0;
    for (const Found& f : found) total += f.power;
    double running = 0.0;
    float below = 0.0f;  // the previous emitter's fraction, as the kernel compares with it
    for (std::size_t i = 0; i < found.size(); ++i) {
        running += found[i].power;
        // Powers too small for double (all below ~1e-300) fall back to equal chances.
        const double cdf = total > 0.0 ? running / total : double(i + 1) / double(found.size());
        // The last exactly 1, whatever the rounding of the sum: the kernel's search for
        // the first fraction above a number in [0, 1) must always end on an emitter.
        const float upto = i + 1 == found.size() ? 1.0f : static_cast<float>(cdf);
        g.emitters.push_back(kernel::Emitter(uvec4(found[i].ref, found[i].part, 0u, 0u), vec4(upto, below, 0.0f, 0.0f)));
        below = upto;
    }
    kernel::set_emitter_count(g.params, static_cast<std::uint32_t>(g.emitters.size()));
    kernel::set_light_samples(g.params, scene.render.light_samples);
    kernel::set_emitter_power(g.params, static_cast<float>(total));
}

template <class Array>
std::size_t bytes(const Array& a) { return a.size() * sizeof(typename Array::value_type); }

// Whether this render walks a grid, and why: the stats report the reason.
bool want_grid(const Scene& scene, std::size_t primitives, const AccelPolicy& policy, std::string& reason) {
    const GridSettings& settings = scene.render.grid;
    if (primitives == 0) {
        reason = "no primitives";
        return false;
    }
    switch (settings.mode) {
    case GridMode::Off:
        reason = "off: requested (render.grid or --grid)";
        return false;
    case GridMode::On:
        reason = "on: requested (render.grid or --grid)";
        return true;
    case GridMode::Uniform:
        reason = "uniform: requested (render.grid or --grid)";
        return true;
    case GridMode::Auto: break;
    }
    if (primitives < policy.brute_force_below) {
        reason = fmt::format("auto: {} primitives, below this backend's measured threshold of {} where the "
                             "grid starts to beat brute force", primitives, policy.brute_force_below);
        return false;
    }
    reason = fmt::format("auto: {} primitives, at or above this backend's threshold of {}", primitives,
                         policy.brute_force_below);
    return true;
}

// At most this many primitives of listed kinds are loose for their size
// (host/accel/grid.cpp, choose_stretching): each costs every ray a test, and a floor
// is two. The brute-force threshold's value today (a scene of 32 primitives renders
// as fast through the grid as by brute force), but a constant of its own, so that
// re-measuring the threshold leaves it alone.
constexpr std::size_t kMaxStretching = 32;

// The kinds loose as a whole (indexed by REF_SPHERE...): a kind with fewer
// primitives than the backend's threshold, the count below which brute force beats
// the grid on a whole scene, is listed in no cell and tested once per ray instead
// (kernel/traversal.glsl, trace). A floor of two triangles under thousands of spheres
// would otherwise be listed in every cell it spans, stretch the grid's box to its
// own size, and cost every cell visited a pass through the triangle loop, which SIMD
// hardware runs even when no lane has a triangle (docs/grid.md). Every kind is
// listed when no kind reaches the threshold (a grid forced on a small scene), and
// when the scene gives the resolution: that asks for one particular grid, over the
// whole scene (the README compares SPD balls with published figures for such grids).
// The primitives of each kind, indexed by kind.
std::array<std::size_t, kernel::PRIMITIVE_KINDS> kind_counts(const FlatScene& g) {
    return {
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) g.names.size(),
#include "kernel/shapes/kinds.glsl"
    };
}

std::array<bool, kernel::PRIMITIVE_KINDS> loose_kinds(const AccelPolicy& policy, bool resolution_given,
                                                      const FlatScene& g) {
    const std::array<std::size_t, kernel::PRIMITIVE_KINDS> counts = kind_counts(g);
    const bool any_large = std::any_of(counts.begin(), counts.end(),
                                       [&](std::size_t n) { return n >= policy.brute_force_below; });
    std::array<bool, kernel::PRIMITIVE_KINDS> loose{};
    for (std::size_t k = 0; k < counts.size(); ++k) {
        loose[k] = counts[k] != 0 && !resolution_given && any_large && counts[k] < policy.brute_force_below;
    }
    return loose;
}

// The features that say which kinds the cells list (GRID_) and which the loose
// references hold (LOOSE_), and the stats' account of the loose ones: a kind loose
// as a whole as "triangles: 2", some of a listed kind as "triangles: 2 of 49294".
void note_kinds(const Grid& grid, const AccelPolicy& policy, const std::array<bool, kernel::PRIMITIVE_KINDS>& whole,
                FlatScene& g) {
    struct Kind {
        Feature listed, loose;
        const char* name;
        std::size_t count;
    };
    const std::array<Kind, kernel::PRIMITIVE_KINDS> kinds{{
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    {Feature::GRID_##NAMES, Feature::LOOSE_##NAMES, #names, g.names.size()},
#include "kernel/shapes/kinds.glsl"
    }};
    std::array<std::size_t, kernel::PRIMITIVE_KINDS> loose{};
    for (std::uint32_t i = 0; i < grid.loose; ++i) ++loose[grid.refs[i] >> kernel::REF_KIND_SHIFT];
    std::vector<std::string> small, stretching;
    for (std::size_t k = 0; k < kinds.size(); ++k) {
        g.features.set(kinds[k].listed, loose[k] < kinds[k].count);
        g.features.set(kinds[k].loose, loose[k] != 0);
        if (whole[k]) {
            small.push_back(fmt::format("{}: {}", kinds[k].name, loose[k]));
        } else if (loose[k] != 0) {
            stretching.push_back(fmt::format("{}: {} of {}", kinds[k].name, loose[k], kinds[k].count));
        }
    }
    if (!small.empty()) {
        g.grid.reason += fmt::format("; tested per ray, outside the grid (fewer than {} of their kind): {}",
                                     policy.brute_force_below, fmt::join(small, ", "));
    }
    if (!stretching.empty()) {
        g.grid.reason += fmt::format("; tested per ray, outside the grid (their boxes would make it {:.0f} times "
                                     "larger): {}", grid.loose_shrink, fmt::join(stretching, ", "));
    }
    g.grid.outside = small;
    g.grid.outside.insert(g.grid.outside.end(), stretching.begin(), stretching.end());
}

void add_grid(const Scene& scene, const AccelPolicy& policy, FlatScene& g) {
    const auto start = std::chrono::steady_clock::now();
    GridRequest request;
    request.resolution = scene.render.grid.resolution;
    // A resolution from the scene asks for a grid over everything.
    const bool resolution_given = request.resolution != GridResolution{0, 0, 0};
    request.loose_kinds = loose_kinds(policy, resolution_given, g);
    request.max_loose = resolution_given ? 0 : kMaxStretching;
    request.max_entries = policy.max_buffer_entries;
    request.eye = scene.camera.eye - g.origin;
    request.split = scene.render.grid.mode != GridMode::Uniform;
    std::string note;
    const GridPrimitives primitives{
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) g.names,
#include "kernel/shapes/kinds.glsl"
    };
    Grid grid = build_grid(primitives, request, note);
    note_kinds(grid, policy, request.loose_kinds, g);
    kernel::Params& p = g.params;
    kernel::set_grid_min(p, vec3(grid.lo));
    kernel::set_grid_max(p, vec3(grid.hi));
    kernel::set_grid_cell(p, vec3(grid.cell));
    kernel::set_grid_inv_cell(p, vec3(1.0 / grid.cell));
    kernel::set_grid_resolution(p, uvec3(grid.resolution[0], grid.resolution[1], grid.resolution[2]));
    g.grid.used = true;
    g.grid.resolution = grid.resolution;
    g.grid.cells = grid.leaves;
    g.grid.levels = grid.levels;
    g.features.set(Feature::GRID_SPLIT, grid.levels > 0);
    g.grid.references = grid.refs.size();
    g.grid.bytes = grid.bytes();
    if (!note.empty()) g.grid.reason += "; " + note;
    g.grid.warning = note;
    g.grid_nodes = std::move(grid.nodes);
    g.grid_refs = std::move(grid.refs);
    g.grid.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The kernel's params.glsl offset_shrink(): 2^-shrink is the smallest power of two
// that is at least every kernel coordinate of the primitives' boxes and of the eye
// (the rays' origins), when that is below 1, so that the offsets of ray.glsl
// (offset_coordinate) shrink with a scene smaller than 1; else 0. Capped at 100,
// 2^-100 ~ 8e-31, which keeps the kernel's exponent arithmetic within floats.
std::uint32_t offset_shrink(const FlatScene& g, const dvec3& eye) {
    constexpr std::uint32_t kMostShrink = 100;
    double most = std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)});
    if (most >= 0.5) return 0;  // the usual case: no pass over the primitives
    const auto take = [&](const Aabb& b) {
        most = std::max({most, std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z), std::abs(b.hi.x),
                         std::abs(b.hi.y), std::abs(b.hi.z)});
    };
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    for (const kernel::Name& primitive : g.names) take(bounds(primitive));
#include "kernel/shapes/kinds.glsl"
    if (most >= 0.5 || !(most > 0.0)) return 0;
    int exponent = 0;
    std::frexp(most, &exponent);  // most = f 2^exponent, f in [0.5, 1): 2^exponent > most
    return std::min(kMostShrink, static_cast<std::uint32_t>(-exponent));
}

}  // namespace

std::vector<BufferSize> FlatScene::built_buffers() const {
    std::vector<BufferSize> out;
#define SCENE_ARRAY(id, name, Element, load, format) \
    if (!name.empty()) out.push_back({#name, bytes(name)});
#include "kernel/arrays.glsl"
    std::sort(out.begin(), out.end(), [](const BufferSize& a, const BufferSize& b) { return a.name < b.name; });
    return out;
}

FlatScene flatten_scene(const Scene& scene, const AccelPolicy& policy) {
    FlatScene g;
    g.features = analyze_features(scene);
    const RenderSettings& r = scene.render;
    g.samples_per_pixel = r.corners ? 1 : r.samples_per_pixel();
    g.instances = scene.instances;
    g.corners = r.corners;

    kernel::Params& p = g.params;
    g.origin = kernel_origin(scene.camera.eye);
    const dvec3& o = g.origin;
    set_camera(scene.camera, r.corners, o, p);
    kernel::set_ambient_light(p, vec3(r.ambient));
    kernel::set_background(p, vec3(r.background));
    kernel::set_image_width(p, r.corners ? scene.camera.width + 1 : scene.camera.width);
    kernel::set_image_height(p, r.corners ? scene.camera.height + 1 : scene.camera.height);
    kernel::set_aa_per_side(p, r.corners ? 1u : r.aa);
    kernel::set_sample_seed(p, r.seed);
    kernel::set_loop_budget(p, r.loop_budget != 0 ? r.loop_budget : kernel::DEFAULT_LOOP_BUDGET);
    kernel::set_max_depth(p, r.max_depth);
    kernel::set_min_ray_weight(p, static_cast<float>(r.min_weight));
    const std::uint32_t estimator = r.estimator == Estimator::Paper ? kernel::ESTIMATOR_PAPER : kernel::ESTIMATOR_PATH;
    const std::uint32_t hemisphere = r.hemisphere == Hemisphere::Angles    ? kernel::HEMISPHERE_ANGLES
                                     : r.hemisphere == Hemisphere::Uniform ? kernel::HEMISPHERE_UNIFORM
                                                                           : kernel::HEMISPHERE_COSINE;
    kernel::set_estimator(p, estimator);
    kernel::set_hemisphere_rule(p, hemisphere);
    kernel::set_max_bounces(p, r.max_bounces);
    kernel::set_sampler_kind(p, r.sampler == Sampler::Sobol ? kernel::SAMPLER_SOBOL : kernel::SAMPLER_HASH);

    // Buffers only the left-out features read are not built (and so not uploaded).
    const bool any_geometry = scene.primitive_count() != 0;
    if (any_geometry) {
        for (const Material& m : scene.materials) g.materials.push_back(flatten(m));
    }
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)                     \
    if (g.features.has(Feature::HAS_##NAMES)) {                                       \
        for (const Name& primitive : scene.names) g.names.push_back(flatten(primitive, o)); \
    }                                                                                 \
    kernel::set_##name##_count(p, static_cast<std::uint32_t>(g.names.size()));
#include "kernel/shapes/kinds.glsl"
    if (g.features.has(Feature::HAS_POINT_LIGHTS)) {
        for (const Light& l : scene.lights) g.lights.push_back(flatten(l, o));
    }
    kernel::set_offset_shrink(p, offset_shrink(g, scene.camera.eye - o));
    kernel::set_light_count(p, static_cast<std::uint32_t>(g.lights.size()));
    kernel::set_material_count(p, static_cast<std::uint32_t>(g.materials.size()));
    if (g.features.has(Feature::HAS_ALPHA)) mark_coverage_tested(scene, g);
    if (g.features.has(Feature::HAS_TEXTURES)) add_textures(scene, g);
    if (g.features.has(Feature::HAS_AREA_LIGHTS)) add_emitters(scene, g);
    // Every emissive primitive kind has its sampler, so the list is empty only if no
    // primitive emits; the kernel's search must never see an empty list.
    if (g.emitters.empty()) g.features.set(Feature::HAS_AREA_LIGHTS, false);
    if (g.features.has(Feature::HAS_ENVIRONMENT_MAP)) add_environment(scene, g);
    if (g.features.has(Feature::HAS_MICROFACET)) add_ggx_tables(g);
    if (g.features.has(Feature::HAS_VERTEX_COLORS)) {
        kernel::set_vertex_color_first_word(p, add_corner_words(scene, [](const Triangle& t) -> const auto& { return t.colors; }, g));
    }
    if (g.features.has(Feature::HAS_SECOND_MAPPING)) {
        kernel::set_second_uv_first_word(p, add_second_uv_words(scene, g));
    }
    if (g.features.has(Feature::HAS_TANGENTS)) {
        kernel::set_tangent_first_word(p, add_corner_words(scene, [](const Triangle& t) -> const auto& { return t.tangents; }, g));
    }
    // Next-event estimation, once it is known what it can sample: emitters, or the
    // environment with a nonzero chance.
    g.features.set(Feature::HAS_NEXT_EVENT,
                   g.features.has(Feature::HAS_GLOBAL) && scene.render.estimator == Estimator::Path && scene.render.nee &&
                       (g.features.has(Feature::HAS_AREA_LIGHTS) || kernel::environment_choice(p) > 0.0f));

    const std::array<std::size_t, kernel::PRIMITIVE_KINDS> counts = kind_counts(g);
    g.grid.used = want_grid(scene, std::accumulate(counts.begin(), counts.end(), std::size_t(0)), policy, g.grid.reason);
    if (g.grid.used) add_grid(scene, policy, g);
    g.features.set(Feature::HAS_GRID, g.grid.used);
    g.features.set(Feature::DEFERRED_SPHERES, !g.grid.used && g.spheres.size() >= policy.deferred_spheres_from);
    return g;
}

}  // namespace vkrt
