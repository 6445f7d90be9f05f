// The kinds of primitive, one line a kind, in the order in which a grid cell lists
// its references (host/accel/grid.cpp) and the traversal tests them. From this table
// are generated: the traversal's loops, one per kind (traversal.glsl: kept apart for
// SIMD hardware, decision 0017); the dispatch from a reference to its kind's hit
// record (traversal.glsl) and light sampling (emitters.glsl); the kinds' reference
// codes (constants.glsl), arrays (arrays.glsl), counts (params.glsl) and features
// (features.glsl); and on the host the scene's arrays, the JSON reader's dispatch, the
// flattening, the emitter list, the grid's boxes and the checks of counts.
//
//   PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)
//
// ID: 0, 1, 2, ... in order: the kind's code in the top bits of a reference
// (constants.glsl, REF_<NAME>), and from it the ids of its array, its count and its
// features.
// name, Name, names, NAME, NAMES: the kind's name as each use needs it: its file
// shapes/<name>.glsl, its record <Name> (defined there), its array <names> and loader
// load_<name> (arrays.glsl), its count <name>_count() (params.glsl), its features
// HAS_<NAMES> (the scene has some), GRID_<NAMES> and LOOSE_<NAMES> (the grid's cells,
// and its loose list, may hold some; features.glsl).
// PARTS: whether a hit records which part of the primitive it met (Nearest.part),
// which then counts as a decision of the trace (budget.glsl, note_decision).
//
// shapes/<name>.glsl defines, under SHAPE_RECORDS, the record <Name> of <names> and
// <Name>_FROM_TEXELS (the rules of layout.glsl, which includes that part), and
// otherwise, beside the kind's intersection itself:
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
// and that part is included by all.glsl after shapes/records.glsl.
//
// The kind's host half, host/scene/shapes/<name>.hpp and .cpp, defines in namespace
// vkrt the scene's record <Name> (Scene::<names>), and:
//
//   void read_shape(const json::Node& object, ShapeReader& reader, std::vector<Name>& out)
//       reads a JSON scene's {"type": "<name>", ...} (host/scene/json_scene_loader.cpp)
//   kernel::<Name> flatten(const Name& primitive, const glm::dvec3& origin)
//       its kernel record, positions relative to origin (host/flatten/flat_scene.cpp)
//   std::uint32_t emitter_parts(const Name& primitive)
//   double emitter_area(const Name& primitive, std::uint32_t part)
//       the emitters it is when its material emits, parts 0 to n - 1 (Emitter.prim.y)
//   Aabb bounds(const kernel::<Name>& record)
//       the box of the record as the kernel intersects it (host/accel/grid.cpp)
//
// The lists of both halves' files are generated from this table
// (cmake/PrimitiveKinds.cmake), so that a new kind is this line and its three files.
// The file that includes this table defines PRIMITIVE_KIND; it is undefined at the end.
PRIMITIVE_KIND(0, sphere, Sphere, spheres, SPHERE, SPHERES, false)
PRIMITIVE_KIND(1, triangle, Triangle, triangles, TRIANGLE, TRIANGLES, false)  // and quads
PRIMITIVE_KIND(2, ring, Ring, rings, RING, RINGS, false)
PRIMITIVE_KIND(3, cylinder, Cylinder, cylinders, CYLINDER, CYLINDERS, true)

#undef PRIMITIVE_KIND
