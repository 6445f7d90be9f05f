#pragma once
// The validated, in-memory scene: what a loader produces and everything downstream
// reads (docs/architecture.md, principle 2). Values stay in double here; they become float only
// when host/flatten/flat_scene.cpp flattens them for a backend.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "image/display.hpp"
#include "scene/environment.hpp"
#include "scene/texture_image.hpp"
#include "scene_shapes.hpp"  // each kind of primitive's host/scene/shapes/<name>.hpp, generated

namespace vkrt {

using glm::dvec3;

struct Camera {
    dvec3 eye{0.0, 0.0, 0.0};
    dvec3 look_at{0.0, 0.0, -1.0};
    dvec3 up{0.0, 1.0, 0.0};
    double fov = 40.0;  // vertical, degrees, in (0, 180)
    std::uint32_t width = 400;
    std::uint32_t height = 300;
    // A thin lens of this radius (0: a pinhole), sharp at focus_distance along the
    // view axis (unset: at look_at).
    double lens_radius = 0.0;
    std::optional<double> focus_distance;
    // Placed by frame_scene (a glTF file without a camera, gltf_loader.hpp), which
    // must place it again when the image's shape changes.
    bool framed = false;
};

// Local: the paper's ray tracer (Phong from lights, the mirror/glass ray tree).
// Global: Monte Carlo global illumination (kernel/global.glsl).
enum class RenderMode { Local, Global };

// Global mode's estimators: the paper's, as written (biased), or unbiased path tracing.
enum class Estimator { Paper, Path };

// How a diffuse bounce draws its direction (kernel/hemisphere.glsl).
enum class Hemisphere { Angles, Uniform, Cosine };

// Where a sample's random numbers come from (kernel/rng.glsl): Owen-scrambled Sobol
// points, or an independent hash per number.
enum class Sampler { Sobol, Hash };

// The grid (host/accel/grid.hpp). Auto builds it unless the scene is small enough
// that brute force is faster on the chosen backend (a measured threshold); Uniform
// builds it and splits no cell, the paper's uniform grid.
enum class GridMode { Auto, On, Off, Uniform };

struct GridSettings {
    GridMode mode = GridMode::Auto;
    // Cells per axis; zeros mean "choose by the heuristic" (docs/grid.md).
    std::array<std::uint32_t, 3> resolution{0, 0, 0};
};

struct RenderSettings {
    RenderMode mode = RenderMode::Local;
    std::uint32_t aa = 1;          // aa x aa sub-pixel rays per pixel (paper's Fig. 6)
    bool jitter = false;           // random position inside each sub-pixel
    bool shadows = true;
    bool terminator = true;        // shadow rays from the smooth surface of smooth triangles
    std::uint32_t max_depth = 5;   // reflection/refraction generations after the eye ray
    double min_weight = 1e-3;      // secondary rays weighing less are not traced (0: all are)
    bool corners = false;          // one ray through each pixel corner, four averaged (SPD)
    dvec3 ambient{0.0};
    dvec3 background{0.0};
    std::uint32_t seed = 0;
    Sampler sampler = Sampler::Sobol;
    std::uint32_t spp = 0;         // samples per pixel; 0 means aa * aa
    std::uint32_t loop_budget = 0; // per-invocation loop iterations; 0 means the kernel default
    // Shadow rays toward the emissive primitives per hit (local mode); 0 turns their
    // lighting off. docs/scene-format.md says why 16.
    std::uint32_t light_samples = 16;
    GridSettings grid;
    // Global mode (docs/scene-format.md, "Global illumination").
    Estimator estimator = Estimator::Path;
    Hemisphere hemisphere = Hemisphere::Cosine;  // the paper estimator's default is Angles
    bool nee = true;                  // path: next-event estimation toward area lights, with MIS
    std::uint32_t max_bounces = 8;    // scattering events after the first hit
    Display display;                  // exposure and tone curve of 8-bit outputs
    // Keep each pixel's sums of squares, from which the variance of its mean follows
    // (HAS_SQUARES): `vkrt render --variance` and partial files ask for them; not a
    // field of the scene file.
    bool squares = false;
    // Keep each pixel's render passes (HAS_PASSES: the first hit's base colour,
    // normal and distance): `vkrt render --passes` asks for them; not a field of the
    // scene file either.
    bool passes = false;

    // Global mode takes 16 samples when neither spp nor aa says otherwise.
    std::uint32_t samples_per_pixel() const {
        if (spp != 0) return spp;
        return mode == RenderMode::Global && aa == 1 ? 16 : aa * aa;
    }
};

enum class AlphaMode : std::uint32_t { Opaque = kernel::ALPHA_OPAQUE, Mask = kernel::ALPHA_MASK, Blend = kernel::ALPHA_BLEND };

struct Material {
    std::string name;
    dvec3 diffuse{0.0};
    double kd = 1.0;
    dvec3 specular{0.0};
    double ks = 0.0;
    double shininess = 20.0;
    dvec3 reflect{0.0};
    dvec3 transmit{0.0};
    double ior = 1.5;
    bool fresnel = true;  // glass splits transmit by the Fresnel reflectance (else constant weights)
    dvec3 emission{0.0};
    // glTF's metallic-roughness model instead of the Phong fields above (which it
    // leaves at their defaults, emission and ior aside): a GGX lobe with reflectance
    // mix(f0, base_color, metallic) at normal incidence, f0 = ((ior - 1) / (ior + 1))^2
    // (0.04 at the default ior 1.5), over a diffuse lobe of (1 - metallic) base_color;
    // with transmission, glass takes that share of the dielectric (kernel/texture.glsl).
    // Global mode only; local mode shades the diffuse lobe.
    struct MetallicRoughness {
        dvec3 base_color{1.0};
        double metallic = 0.0;      // 0 to 1
        double roughness = 1.0;     // 0 to 1; the GGX alpha is its square
        double transmission = 0.0;  // 0 to 1 (glTF's KHR_materials_transmission)
        // The glass is a thin wall, crossed without refraction (glTF's transmission
        // without KHR_materials_volume), rather than the surface of a solid.
        bool thin = false;
        // What the solid glass absorbs (glTF's KHR_materials_volume): light keeps
        // attenuation_color after attenuation_distance (world units) inside it, Beer
        // and Lambert's law between; white or an infinite distance is clear glass.
        dvec3 attenuation_color{1.0};
        double attenuation_distance = std::numeric_limits<double>::infinity();
        // A clear coat over it all (glTF's KHR_materials_clearcoat): a dielectric layer
        // of ior 1.5 and this roughness, weighted by `clearcoat` (kernel/lobes/coat.glsl).
        double clearcoat = 0.0;            // 0 to 1
        double clearcoat_roughness = 0.0;  // 0 to 1
        // Sheen over it, under the coat (glTF's KHR_materials_sheen; kernel/lobes/sheen.glsl).
        dvec3 sheen_color{0.0};         // each 0 to 1; black: none
        double sheen_roughness = 0.0;   // 0 to 1
        // The dielectric's specular layer (glTF's KHR_materials_specular): it reflects
        // min(f0 specular_color, 1) specular at normal incidence, f0 from the ior, and
        // `specular` at grazing incidence; the diffuse lobe takes what it leaves. The
        // metal and the glass are not affected.
        double specular = 1.0;           // 0 to 1
        dvec3 specular_color{1.0};       // each at least 0
        bool has_specular() const { return specular != 1.0 || specular_color != dvec3(1.0); }
        // Whether light crossing it is absorbed: solid glass with some attenuation.
        bool absorbs() const {
            return transmission > 0.0 && metallic < 1.0 && !thin && std::isfinite(attenuation_distance) &&
                   attenuation_color != dvec3(1.0);
        }
    };
    std::optional<MetallicRoughness> metallic_roughness;
    // A colour texture (an index into Scene::textures) multiplying `diffuse`, or the
    // base colour; read at the texture coordinates (u, v) taken through
    // uv_transform: u' = [0] u + [1] v + [2], v' = [3] u + [4] v + [5].
    std::optional<std::uint32_t> texture;
    // With metallic_roughness: a linear texture whose blue channel multiplies
    // metallic and green roughness (glTF's), at the same coordinates.
    std::optional<std::uint32_t> metallic_roughness_texture;
    // A normal map, at the same coordinates: a texture of tangent-space normals in
    // glTF's encoding, with its scale (TextureImage::normal_scale).
    std::optional<std::uint32_t> normal_map;
    // An emission texture, at the same coordinates: multiplies `emission` (which
    // must be nonzero for the material to emit at all).
    std::optional<std::uint32_t> emission_texture;
    // With metallic_roughness transmission: a linear texture whose red channel
    // multiplies the transmission (glTF's transmissionTexture), at the same coordinates.
    std::optional<std::uint32_t> transmission_texture;
    // With metallic_roughness layers (kernel/texture.glsl, apply_layer_textures), at the
    // same coordinates: linear textures whose red channel multiplies clearcoat and
    // whose green multiplies clearcoat_roughness (glTF's clearcoatTexture and
    // clearcoatRoughnessTexture); a colour texture multiplying sheen_color and a linear
    // one whose alpha multiplies sheen_roughness (glTF's sheen textures).
    std::optional<std::uint32_t> clearcoat_texture;
    std::optional<std::uint32_t> clearcoat_roughness_texture;
    std::optional<std::uint32_t> sheen_color_texture;
    std::optional<std::uint32_t> sheen_roughness_texture;
    // With a clear coat: the coat's own normal map, encoded and scaled as normal_map
    // is (glTF's clearcoatNormalTexture). Without one the coat lies on the surface's
    // normal, which normal_map does not bend (kernel/normal_map.glsl, coat_normal).
    std::optional<std::uint32_t> clearcoat_normal_map;
    // With metallic_roughness: the dielectric's specular textures (glTF's
    // KHR_materials_specular, kernel/texture.glsl apply_specular_textures), at the same
    // coordinates: a linear texture whose alpha multiplies `specular` (specularTexture)
    // and a colour texture multiplying `specular_color` (specularColorTexture).
    std::optional<std::uint32_t> specular_texture;
    std::optional<std::uint32_t> specular_color_texture;
    // Every texture slot above, for what treats them alike, in the order of the
    // kernel's MAP_<slot> numbers (kernel/constants.glsl).
    std::array<std::optional<std::uint32_t>*, kernel::MAP_SLOTS> texture_slots() {
        return {&texture, &metallic_roughness_texture, &normal_map, &emission_texture, &transmission_texture,
                &clearcoat_texture, &clearcoat_roughness_texture, &sheen_color_texture, &sheen_roughness_texture,
                &clearcoat_normal_map, &specular_texture, &specular_color_texture};
    }
    bool textured() const {
        return texture || metallic_roughness_texture || normal_map || emission_texture || transmission_texture ||
               clearcoat_texture || clearcoat_roughness_texture || sheen_color_texture || sheen_roughness_texture ||
               clearcoat_normal_map || specular_texture || specular_color_texture;
    }
    std::array<double, 6> uv_transform{1.0, 0.0, 0.0, 0.0, 1.0, 0.0};
    // A second mapping of texture coordinates (kernel/texture.glsl), for textures that
    // glTF puts on another TEXCOORD_<n> or KHR_texture_transform than the first
    // texture's: the textures whose bit 1 << kernel::MAP_<slot> `maps` has read the
    // triangles' second coordinates (Triangle::second_uvs) where own_coordinates is
    // set, else their first ones, through `transform` (as uv_transform). The colour
    // texture always reads the first mapping.
    struct SecondMapping {
        std::uint32_t maps = 0;  // none: no texture reads it
        bool own_coordinates = false;
        std::array<double, 6> transform{1.0, 0.0, 0.0, 0.0, 1.0, 0.0};
    };
    SecondMapping second_mapping;
    // Whether the texture in slot `slot` (kernel::MAP_<slot>) reads the second mapping.
    bool on_second_mapping(std::uint32_t slot) const { return (second_mapping.maps >> slot & 1u) != 0u; }
    // Coverage (glTF's alphaMode; kernel/alpha.glsl): the opacity at a point is
    // `alpha` times the colour texture's alpha there. Mask: the surface is there
    // where the opacity reaches alpha_cutoff; blend: with probability the opacity.
    // Triangles and quads only: other shapes have no texture coordinates.
    AlphaMode alpha_mode = AlphaMode::Opaque;
    double alpha = 1.0;         // 0 to 1
    double alpha_cutoff = 0.5;  // 0 to 1, for a mask
};

enum class LightType { Point, Spot, Directional };

// One of the scene's `lights` (docs/scene-format.md): a point, a spot light (a point
// that shines into a cone) or a directional light (a light at infinity).
struct Light {
    dvec3 position{0.0};  // point and spot
    dvec3 color{1.0};
    // Multiplies color: an intensity for point and spot lights, the irradiance on a
    // surface facing it for a directional light.
    double intensity = 1.0;
    LightType type = LightType::Point;
    // Spot and directional: the way the light travels, unit length (the loaders
    // normalize it).
    dvec3 direction{0.0, -1.0, 0.0};
    // Spot: the cone's half-angles from the axis, in radians, 0 <= inner < outer <=
    // pi/2; full intensity within inner, none beyond outer, glTF's falloff between.
    double inner_angle = 0.0;
    double outer_angle = 0.25 * 3.14159265358979323846;
};

struct InstanceCounts {
    std::size_t meshes = 0;
    std::size_t placements = 0;
};

struct Scene {
    std::filesystem::path source;  // the file it came from, for messages
    Camera camera;
    RenderSettings render;
    std::vector<Material> materials;
    std::vector<Light> lights;
    // One array per kind of primitive (shaders/kernel/shapes/kinds.glsl): spheres,
    // triangles, rings, cylinders. Each kind's record is in host/scene/shapes/<name>.hpp.
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) std::vector<Name> names;
#include "kernel/shapes/kinds.glsl"
    std::vector<TextureImage> textures;  // Material::texture indexes them
    TexelStore texels;                   // every texture's texels (TextureImage::first_word)
    // The image around the scene; without it rays that leave see render.background.
    std::optional<Environment> environment;
    // Wall-clock seconds the loader spent decoding texture images (for the stats).
    double texture_decode_seconds = 0.0;
    // Meshes placed more than once (glTF nodes sharing a mesh, EXT_mesh_gpu_instancing,
    // the scene format's "instance"): how many, and their placements in all, each a
    // copy of the mesh's triangles (for the stats).
    InstanceCounts instances;
    // What the loader accepted but the renderer will not show as the file means it
    // (e.g. an NFF mirror before mirrors exist); printed as warnings before rendering.
    std::vector<std::string> warnings;

    // Primitives of every kind: what the grid holds and the kernel tests.
    std::size_t primitive_count() const {
        return 0
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) +names.size()
#include "kernel/shapes/kinds.glsl"
            ;
    }
};

}  // namespace vkrt
