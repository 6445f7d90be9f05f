// The whole kernel, in dependency order. Included by shaders/render.comp and, inside
// the reference Kernel struct, by host/ref/kernel.hpp. Before including it, a host
// declares the feature flags (features.glsl), `params`, and the accessors
// load_material, load_sphere, load_triangle, load_light, load_ring, load_cylinder and
// load_emitter (uint index -> struct), the grid's load_cell_start and load_ref
// (uint index -> uint), and load_grid_sphere (uint position, uint index -> vec4: the
// center and radius of the sphere that reference `position` lists, sphere `index`;
// each host reads whichever of the two it reads faster).
#include "rng.glsl"
#include "ray.glsl"
#include "intersect.glsl"
#include "budget.glsl"
#include "camera.glsl"
#include "grid.glsl"
#include "scene.glsl"
#include "hemisphere.glsl"
#include "phong.glsl"
#include "visibility.glsl"
#include "emitters.glsl"
#include "area_lights.glsl"
#include "shade.glsl"
#include "specular.glsl"
#include "sample_result.glsl"
#include "bsdf.glsl"
#include "global.glsl"
#include "sample.glsl"
