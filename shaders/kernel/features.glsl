// The feature set: one entry per part of the kernel that a scene may not need.
// Each side defines FEATURE(id, NAME) before including this file:
//   GLSL   -> a boolean specialization constant with constant_id = id (default true),
//   kernel -> a bool member of the reference Kernel struct,
//   host   -> the Feature enum and its names (host/flatten/features.hpp).
// Ids are dense, 0 to count - 1 (host/flatten/features.hpp checks).
// A feature that is false is compiled out of the pipeline by the driver, and the
// buffers only it reads are neither built nor uploaded.
FEATURE(0, HAS_SMOOTH_NORMALS)
FEATURE(1, HAS_POINT_LIGHTS)   // the scene's `lights`, of any kind: the loop over them (lights.glsl)
FEATURE(2, HAS_SHADOWS)
FEATURE(3, HAS_SPECULAR)
FEATURE(4, HAS_AMBIENT)
FEATURE(5, HAS_EMISSION)
FEATURE(6, HAS_JITTER)
FEATURE(7, HAS_GRID)
FEATURE(8, HAS_AREA_LIGHTS)  // the emitter list (emitters.glsl), sampled by local mode's light samples or HAS_NEXT_EVENT
FEATURE(9, HAS_REFLECTION)   // mirror rays (material reflect)
FEATURE(10, HAS_REFRACTION)   // refraction rays, and the reflection rays of glass (material transmit, or transmission)
FEATURE(11, HAS_GLOBAL)       // global illumination (global.glsl) instead of the local ray tree
// Without the grid, whether the sphere loop tests the spheres a ray starts near
// after it (deferred_spheres.glsl) rather than in place: on from
// AccelPolicy::deferred_spheres_from spheres (host/accel/accel_policy.hpp), where it
// pays on lavapipe.
FEATURE(12, DEFERRED_SPHERES)
// Triangle records that hold parallelograms (quads): the triangle test becomes the
// quad test, which takes a triangle as a quad with p3 = p2 (shapes/triangle.glsl).
FEATURE(13, HAS_QUADS)
// With HAS_GRID, whether any cell is split into children (host/accel/grid_split.cpp):
// without it every cell is a root cell, found in one step, as in a uniform grid.
FEATURE(14, GRID_SPLIT)
// Shadow rays of smooth triangles leave from the smooth surface their normals
// describe (terminator.glsl): on with smooth normals and shadows, unless the scene
// turns it off (render.terminator; the SPD rules do, to count rays as published).
FEATURE(15, HAS_TERMINATOR)
// A thin lens instead of the pinhole (camera.glsl): the camera's lens_radius > 0.
FEATURE(16, HAS_LENS)
// The metallic-roughness material's GGX lobe (lobes/ggx.glsl): global mode with a
// material that has one.
FEATURE(17, HAS_MICROFACET)
// Colour textures (texture.glsl): a material that the scene uses has one.
FEATURE(18, HAS_TEXTURES)
// Spot or directional lights among the `lights`: their cone and direction (lights.glsl).
// Without it every light is a point light, read and shaded as such, at no extra cost.
FEATURE(19, HAS_DIRECTED_LIGHTS)
// An equirectangular image around the scene instead of the one-colour background,
// and in global mode a light that next-event estimation samples (environment.glsl).
FEATURE(20, HAS_ENVIRONMENT_MAP)
// Normal maps (normal_map.glsl): a triangle's material has one.
FEATURE(21, HAS_NORMAL_MAPS)
// Global mode's next-event estimation (global.glsl, render.nee): each vertex of a
// path draws a point on the emitters (HAS_AREA_LIGHTS) or a direction of the
// environment image, weighted by multiple importance sampling. Only the path
// estimator does; the scene's `lights` are shaded at every vertex without it.
FEATURE(22, HAS_NEXT_EVENT)
// Triangles whose material is not opaque (alphaMode MASK or BLEND): the traversal
// tests their coverage where a ray meets them (alpha.glsl).
FEATURE(23, HAS_ALPHA)
// Triangles with vertex colours (glTF's COLOR_0): they multiply the colour and the
// opacity of the material (vertex_data.glsl).
FEATURE(24, HAS_VERTEX_COLORS)
// Normal-mapped triangles with the file's own tangents (glTF's TANGENT) instead of
// those derived from the texture coordinates (normal_map.glsl).
FEATURE(25, HAS_TANGENTS)
// Glass that absorbs what crosses it (glTF's KHR_materials_volume attenuation): global
// mode weighs each path segment inside it by Beer and Lambert's law (lobes/glass.glsl).
FEATURE(26, HAS_ABSORPTION)
// A clear coat over a metallic-roughness material (lobes/coat.glsl).
FEATURE(27, HAS_COAT)
// Sheen over a metallic-roughness material (lobes/sheen.glsl), with its albedo table.
FEATURE(28, HAS_SHEEN)
// Rough glass (lobes/rough_glass.glsl), with its albedo table: a metallic-roughness
// material with transmission and a roughness above MIN_GGX_ALPHA's square root.
FEATURE(29, HAS_ROUGH_GLASS)
// A metallic-roughness material whose dielectric reflects other than its ior says
// (glTF's KHR_materials_specular): the GGX lobe's Fresnel rises to ggx_f90 at
// grazing incidence instead of 1 (lobes/fresnel.glsl).
FEATURE(30, HAS_DIELECTRIC_SPECULAR)
// A material whose textures read two mappings of texture coordinates (glTF's
// texCoord or KHR_texture_transform differing between them): texture.glsl's
// second_maps, and the triangles' second coordinates (vertex_data.glsl).
FEATURE(31, HAS_SECOND_MAPPING)
// Each pixel's sums of squares beside its sums (sums.glsl): the render's output asks
// for the variance of the mean (vkrt render --variance, partial files).
FEATURE(32, HAS_SQUARES)
// Each pixel's render passes beside its sums (layout.glsl's PassSums): the first
// hit's base colour, shading normal and distance (vkrt render --passes).
FEATURE(33, HAS_PASSES)
// Three per kind of primitive (shapes/kinds.glsl), after the others: HAS_<NAMES>, the
// scene has some; with HAS_GRID, GRID_<NAMES>, the grid's cells list some, and
// LOOSE_<NAMES>, its loose primitives, which are tested once per ray instead, hold
// some: a kind with few primitives as a whole, and the few primitives of other kinds
// whose boxes would stretch the grid's (host/flatten/flat_scene.cpp,
// host/accel/grid.cpp, docs/grid.md).
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    FEATURE((34 + 3 * ID), HAS_##NAMES) FEATURE((34 + 3 * ID + 1), GRID_##NAMES) FEATURE((34 + 3 * ID + 2), LOOSE_##NAMES)
#include "shapes/kinds.glsl"
