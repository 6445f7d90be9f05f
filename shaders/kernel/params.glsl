// The per-render constants, each declared once, here, and read by name: the kernel
// calls max_depth(), the host writes it with set_max_depth(params, value)
// (host/kernel/types.hpp). Params is PARAM_TEXELS 16-byte texels of four 32-bit
// lanes, uploaded as they are; a float lane holds the float's bits. No two values
// share a lane (host/kernel/types.hpp checks it when it compiles).
//
//   PARAM(type, name, texel, lane)   a uint or float in lane x, y, z or w of a texel
//   PARAM3(type, name, texel)        a vec3 or uvec3 in lanes xyz of a texel (w may hold a PARAM)
//
// The file that includes this one defines the two macros; they are undefined at the end.

// The camera (kernel/camera.glsl): the ray through continuous image position (x, y),
// in pixels from the top-left corner, leaves camera_eye() in direction
// camera_corner() + x * camera_right() + y * camera_down(). Positions are relative to
// the flattened scene's origin (docs/decisions/0008-eye-centred-coordinates.md).
PARAM3(vec3, camera_eye, 0)
// The scale 2^-offset_shrink() of a scene smaller than 1 (its primitives and eye within
// 1/2 of the origin; 0 for any other): ray.glsl's offsets off a surface shrink with it
// (docs/decisions/0053-ray-offsets-at-small-scales.md).
PARAM(uint, offset_shrink, 0, w)
PARAM3(vec3, camera_corner, 1)
PARAM3(vec3, camera_right, 2)
PARAM3(vec3, camera_down, 3)
PARAM3(vec3, ambient_light, 4)       // rgb, local shading's ambient term
PARAM3(vec3, background, 5)          // rgb radiance of rays that hit nothing

PARAM(uint, image_width, 6, x)
PARAM(uint, image_height, 6, y)
PARAM(uint, aa_per_side, 6, z)       // an aa x aa grid of samples per pixel
PARAM(uint, sample_seed, 6, w)

// How many entries of each scene array the kernel reads.
PARAM(uint, light_count, 7, x)       // point lights
PARAM(uint, material_count, 7, y)
PARAM(uint, emitter_count, 7, z)     // emissive primitives, for area lights (kernel/emitters.glsl)
PARAM(uint, light_samples, 7, w)     // shadow rays each hit sends toward the emitters

// Bounds on one invocation's work (kernel/budget.glsl) and on the ray tree (sample.glsl).
PARAM(uint, loop_budget, 8, x)       // loop iterations before the sample is given up
PARAM(uint, max_depth, 8, y)         // reflection and refraction generations after the eye ray
PARAM(float, min_ray_weight, 8, z)   // secondary rays of a smaller weight are dropped (0: none)
PARAM(float, emitter_power, 8, w)    // total power of the emitters over pi: sum of area * mean radiance

// Global illumination (kernel/global.glsl).
PARAM(uint, estimator, 9, x)        // ESTIMATOR_*
PARAM(uint, hemisphere_rule, 9, y)  // HEMISPHERE_*
PARAM(uint, max_bounces, 9, z)      // scattering events after the first hit
PARAM(uint, sampler_kind, 9, w)     // SAMPLER_* (rng.glsl)

// The grid (kernel/grid.glsl, host/accel/grid.cpp): root cell (i, j, k) spans
// grid_min() + (i, j, k) * grid_cell() to grid_min() + (i+1, j+1, k+1) * grid_cell();
// grid_max() bounds the box rays are clipped to.
PARAM3(vec3, grid_min, 10)
PARAM3(vec3, grid_max, 11)
PARAM3(vec3, grid_cell, 12)
PARAM3(vec3, grid_inv_cell, 13)      // 1 / grid_cell(), per axis
PARAM3(uvec3, grid_resolution, 14)   // root cells per axis

// A thin lens (kernel/camera.glsl, HAS_LENS).
PARAM(float, lens_scale, 15, x)      // the lens radius over a pixel's width on the plane at distance 1
PARAM(float, focus_distance, 15, y)  // along the view axis, to the plane in focus

// The environment image (kernel/environment.glsl, HAS_ENVIRONMENT_MAP).
PARAM(uint, environment_first_word, 15, z)  // where its header starts in table_words
PARAM(float, environment_choice, 15, w)     // the chance next-event estimation picks it (0: never)

// The rough lobe's albedo tables (kernel/lobes/ggx_multiple.glsl, HAS_MICROFACET).
PARAM(uint, ggx_table_first_word, 16, x)    // where they start in table_words

// Vertex colours (kernel/vertex_data.glsl, HAS_VERTEX_COLORS): six words a triangle.
PARAM(uint, vertex_color_first_word, 16, y)  // where they start in table_words
// Vertex tangents (kernel/vertex_data.glsl, HAS_TANGENTS): six words a triangle.
PARAM(uint, tangent_first_word, 16, z)       // where they start in table_words
// Second texture coordinates (kernel/vertex_data.glsl, HAS_SECOND_MAPPING): six words a triangle.
PARAM(uint, second_uv_first_word, 16, w)     // where they start in table_words

// Each kind of primitive's count (shapes/kinds.glsl), <name>_count(): four a texel
// from PARAM_KIND_TEXEL on (layout.glsl), kind ID in lane ID % 4 (at most 7 kinds,
// constants.glsl).
#define KIND_LANE_0 x
#define KIND_LANE_1 y
#define KIND_LANE_2 z
#define KIND_LANE_3 w
#define KIND_LANE_4 x
#define KIND_LANE_5 y
#define KIND_LANE_6 z
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    PARAM(uint, name##_count, (PARAM_KIND_TEXEL + ID / 4), KIND_LANE_##ID)
#include "shapes/kinds.glsl"
#undef KIND_LANE_0
#undef KIND_LANE_1
#undef KIND_LANE_2
#undef KIND_LANE_3
#undef KIND_LANE_4
#undef KIND_LANE_5
#undef KIND_LANE_6

#undef PARAM3
#undef PARAM
