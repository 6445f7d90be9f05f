// The whole kernel, in dependency order. Included by shaders/render.comp and, inside
// the reference Kernel struct, by host/kernel/kernel.hpp. Before including it, a host
// declares the feature flags (features.glsl), `params` (a Params), its buffers
// (arrays.glsl) and LOAD_ELEMENT (loads.glsl).
#include "param_access.glsl"
#include "loads.glsl"
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
