// The kinds of primitive, one line a kind, in the order in which a grid cell lists
// its references (host/accel/grid.cpp) and the traversal tests them. From this table
// the traversal's loops, one per kind (traversal.glsl: kept apart for SIMD hardware,
// decision 0017), and the dispatch from a reference to its kind's hit record
// (traversal.glsl) and light sampling (emitters.glsl) are generated.
//
//   PRIMITIVE_KIND(REF, name, FEATURE, GRID, LOOSE, PARTS)
//
// REF: the kind's code in the top bits of a reference (constants.glsl, REF_).
// name: its file shapes/<name>.glsl, its array (arrays.glsl: load_<name>) and its
// count (params.glsl: <name>_count).
// FEATURE: the feature without which the scene has none (features.glsl); GRID and
// LOOSE: the features saying the grid's cells and its loose list may hold the kind.
// PARTS: whether a hit records which part of the primitive it met (Nearest.part),
// which then counts as a decision of the trace (budget.glsl, note_decision).
//
// shapes/<name>.glsl defines, beside the kind's intersection itself:
//
//   void test_<name>(Ray ray, uint index, bool any_hit, INOUT(Nearest) nearest)
//       one intersection test, counted (g_intersection_tests): updates `nearest`
//       where the primitive is met before nearest.t; with any_hit (a shadow ray)
//       it may set only nearest.ref, the trace ending there
//   Hit <name>_hit(Ray ray, uint index, Nearest nearest)
//       the hit record of the nearest hit, normals turned toward the ray
//   float <name>_pick_weight(uint index, Material m)
//       the weight by which the host picks the primitive as an emitter
//       (host/flatten/flat_scene.cpp): its density over area is this over
//       emitter_power()
//   EmitterPoint <name>_emitter_point(uint index, uint part, float u1, float u2)
//       a point uniform by area on the emitter (part: Emitter.prim.y)
//   bool <name>_light_sample(vec3 o, uint index, vec2 u, INOUT(LightSample) drawn)
//       a light sample drawn over the solid angle the emitter covers from o, where
//       the kind can and it pays; false: draw by area (<name>_emitter_point)
//   bool <name>_light_pdf(vec3 o, uint index, float area_density, INOUT(float) pdf)
//       the density of <name>_light_sample at the direction of a hit, with the
//       same choice of technique; false where it draws by area
//
// and is included by all.glsl after shapes/records.glsl. The file that includes this
// table defines PRIMITIVE_KIND; it is undefined at the end.
PRIMITIVE_KIND(REF_SPHERE, sphere, HAS_SPHERES, GRID_SPHERES, LOOSE_SPHERES, false)
PRIMITIVE_KIND(REF_TRIANGLE, triangle, HAS_TRIANGLES, GRID_TRIANGLES, LOOSE_TRIANGLES, false)  // and quads
PRIMITIVE_KIND(REF_RING, ring, HAS_RINGS, GRID_RINGS, LOOSE_RINGS, false)
PRIMITIVE_KIND(REF_CYLINDER, cylinder, HAS_CYLINDERS, GRID_CYLINDERS, LOOSE_CYLINDERS, true)

#undef PRIMITIVE_KIND
