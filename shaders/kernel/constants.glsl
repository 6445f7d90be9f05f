// Constants shared by both hosts.

// Lanes of the per-pixel Counters (layout.glsl). Counting per pixel, not with atomics,
// keeps the hot path contention-free; the host sums the lanes after read-back.
// Counters.rays:
const uint RAYS_EYE = 0u;
const uint RAYS_SHADOW = 1u;
const uint RAYS_REFLECTION = 2u;
const uint RAYS_REFRACTION = 3u;
// Counters.work:
const uint WORK_CELLS = 0u;       // grid cells stepped through
const uint WORK_TESTS = 1u;       // ray-primitive intersection tests
const uint WORK_TRUNCATED = 2u;   // samples stopped by the loop budget
const uint WORK_NONFINITE = 3u;   // samples discarded for a NaN or infinite value
// Counters.tree:
const uint TREE_EYE_HITS = 0u;       // eye rays that hit something (an SPD count)
const uint TREE_DROPPED_WEIGHT = 1u; // secondary rays not traced: weight below min_ray_weight()
const uint TREE_DROPPED_STACK = 2u;  // secondary rays not traced: the pending-ray stack was full
const uint TREE_DECISIONS = 3u;      // sum of the samples' decision hashes (budget.glsl)
// Counters.paths (global mode, global.glsl):
const uint PATHS_BOUNCE_RAYS = 0u;    // rays traced after a scattering event
const uint PATHS_ROULETTE = 1u;       // paths ended by Russian roulette
const uint PATHS_PAPER_DROPPED = 2u;  // paper-estimator samples whose gl() was 0: left out of the average
// Counters.paths.w is unused (0).
// Cells and tests cannot overflow a pixel's 32-bit lane: each is at most one loop
// iteration, a sample has at most kMaxLoopBudget (65,000) of those, and a pixel at
// most 65,536 samples: 65,000 * 65,536 < 2^32. (Only the cpu backend can lift the
// budget, for benchmarks at one sample per pixel.)

// The discrete decisions a sample hashes (note_decision, budget.glsl), one code each,
// so that two samples that branched differently hash differently. Besides these, the
// hash takes the primitive reference of every hit and the part of a cylinder hit.
const uint DECISION_UNBLOCKED = 0u;          // a shadow ray reached its light (traversal.glsl)
const uint DECISION_BLOCKED = 1u;            // ... or something blocked it
const uint DECISION_LIGHT_BEHIND = 2u;       // the light lies behind the surface: no shadow ray (visibility.glsl)
const uint DECISION_LIGHT_FACING = 3u;       // ... or in front of it
const uint DECISION_RAY_QUEUED = 4u;         // a secondary ray was queued (sample.glsl)
const uint DECISION_RAY_TOO_LIGHT = 5u;      // ... or dropped for its weight
const uint DECISION_REFRACTED = 6u;          // the ray tree's glass refracted (sample.glsl)
const uint DECISION_TOTAL_REFLECTION = 7u;   // ... or reflected totally
const uint DECISION_BACK_FACE = 8u;          // a ray hit a back face (traversal.glsl)
const uint DECISION_FRONT_FACE = 9u;         // ... or a front face
const uint DECISION_NORMAL_KEPT = 10u;       // the shading normal was on the viewer's side (shapes/triangle.glsl)
const uint DECISION_NORMAL_FLIPPED = 11u;    // ... or was flipped to it
const uint DECISION_SMOOTH_LOBES = 12u;      // a path sampled the smooth lobes (global.glsl)
const uint DECISION_MIRROR = 13u;            // ... the mirror
const uint DECISION_GLASS_REFLECTS = 14u;    // ... the glass, which reflected
const uint DECISION_GLASS_REFRACTS = 15u;    // ... the glass, which refracted
const uint DECISION_ROULETTE_ENDED = 16u;    // Russian roulette ended a path (global.glsl)
const uint DECISION_OUTSIDE_CONE = 17u;      // a point lay outside a spot light's cone (lights.glsl)
const uint DECISION_INSIDE_CONE = 18u;       // ... or inside it

// A grid cell's primitive reference: the primitive's kind in the top 3 bits, its
// index into that kind's buffer in the low 29 (so at most 2^29 primitives of one
// kind; host/accel/grid.cpp refuses more). The kinds are those of shapes/kinds.glsl,
// REF_SPHERE = 0 and on; REF_NONE is kind 7, which no primitive has, so it cannot be
// mistaken for a real reference.
const uint REF_KIND_SHIFT = 29u;
const uint REF_INDEX_MASK = (1u << REF_KIND_SHIFT) - 1u;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) const uint REF_##NAME = uint(ID);
#include "shapes/kinds.glsl"
const uint PRIMITIVE_KINDS = 0u
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) + 1u
#include "shapes/kinds.glsl"
    ;
const uint REF_NONE = 0xFFFFFFFFu;  // "no primitive": kind 7, which no primitive has

// The grid (kernel/grid.glsl, host/accel/grid.cpp and grid_split.cpp). A root cell spans
// GRID_FINE fine units per axis; a point's fine coordinate is its root cell's index
// times GRID_FINE plus its place within it, so root resolutions up to
// 2^(32 - GRID_FRACTION_BITS) per axis fit a uint. An inner cell splits into
// 4 x 4 x 4 children, each a quarter of it per axis, at most GRID_MAX_LEVELS deep.
const uint GRID_FRACTION_BITS = 14u;
const float GRID_FINE = 16384.0f;                  // 2^GRID_FRACTION_BITS
const uint GRID_SPLIT_BITS = 2u;                   // children per axis: 2^GRID_SPLIT_BITS
const uint GRID_MAX_LEVELS = GRID_FRACTION_BITS / GRID_SPLIT_BITS;
const uint GRID_CHILDREN = 1u << (3u * GRID_SPLIT_BITS);
// A node is one word, the offset of its references in grid_refs, and they end where
// the next node's begin: the uniform grid's prefix sum of cell sizes. With GRID_INNER
// set, an inner cell, which has one reference: the node of its first child (children
// x fastest, then y, then z).
const uint GRID_INNER = 0x80000000u;

// The part of a cylinder a ray hit (CylinderHit in shapes/cylinder.glsl).
const uint CYLINDER_SIDE = 0u;
const uint CYLINDER_BASE_CAP = 1u;
const uint CYLINDER_TOP_CAP = 2u;

// What a Triangle record holds (Triangle.meta.z): a triangle p0 p1 p2, or the
// parallelogram p0, p1, p2, p0 + p2 - p1 (a scene file's quad), which is a rectangle
// when its edges are perpendicular (an emissive one is sampled by solid angle).
const uint SHAPE_TRIANGLE = 0u;
const uint SHAPE_PARALLELOGRAM = 1u;
const uint SHAPE_RECTANGLE = 2u;
// Flags of a Triangle record (Triangle.meta.y): the scene gave vertex normals; its
// material's coverage is tested where a ray meets it (alpha.glsl); it has vertex
// colours; it has vertex tangents.
const uint TRIANGLE_NORMALS = 1u;
const uint TRIANGLE_ALPHA_TESTED = 2u;
const uint TRIANGLE_COLORS = 4u;        // it has vertex colours (vertex_data.glsl)
const uint TRIANGLE_TANGENTS = 8u;      // it has vertex tangents (vertex_data.glsl)

// A material's coverage (Material.alpha_mode, alpha.glsl), glTF's alphaMode.
const uint ALPHA_OPAQUE = 0u;
const uint ALPHA_MASK = 1u;    // opaque where the opacity reaches the cutoff, absent elsewhere
const uint ALPHA_BLEND = 2u;   // present with probability equal to the opacity

// A material's texture slots, numbered for Material.second_maps (bit 1 << MAP_<slot>:
// the texture reads the second mapping, texture.glsl) in the host's order
// (Material::texture_slots). The colour texture always reads the first mapping, so
// that coverage (alpha.glsl) needs one.
const uint MAP_COLOR = 0u;
const uint MAP_METAL_ROUGH = 1u;
const uint MAP_NORMAL = 2u;
const uint MAP_EMISSION = 3u;
const uint MAP_TRANSMISSION = 4u;
const uint MAP_COAT = 5u;
const uint MAP_COAT_ROUGH = 6u;
const uint MAP_SHEEN = 7u;
const uint MAP_SHEEN_ROUGH = 8u;
const uint MAP_COAT_NORMAL = 9u;
const uint MAP_SPECULAR = 10u;
const uint MAP_SPECULAR_COLOR = 11u;
const uint MAP_SLOTS = 12u;

// The narrowest GGX lobe (lobes/ggx.glsl): alpha = roughness^2 down to
// this, so that a roughness of 0 (a polished metal) stays a lobe that next-event
// estimation and MIS can weigh. Its peak, 1 / (pi alpha^2), is far inside float's range.
const float MIN_GGX_ALPHA = 0.001f;
// The sheen's narrowest distribution (lobes/sheen.glsl): roughness 9/31 (0.29), a
// knot of the albedo table, exponent 1/alpha at most 12. Narrower ones put their
// albedo into a sliver of grazing directions where it changes faster than the
// table's knots follow (host/flatten/sheen_albedo.cpp): against quadrature it was
// 26% off at roughness 0.05 and 9% at 0.15 (cos 0.3) (decisions/0044-sheen.md).
const float MIN_SHEEN_ALPHA = 81.0f / 961.0f;
// Knots per axis of the rough lobe's albedo tables (lobes/ggx_multiple.glsl).
const uint GGX_TABLE_SIZE = 32u;
// Rough glass's albedo table (lobes/rough_glass.glsl): knots of log(eta) evenly from
// -log(ROUGH_GLASS_ETA_MAX) to +log(ROUGH_GLASS_ETA_MAX), eta = 1 among them; a
// ratio of indices beyond takes the last knot's albedo.
const uint ROUGH_GLASS_ETA_KNOTS = 33u;
const float ROUGH_GLASS_ETA_MAX = 3.0f;

// How a texture continues beyond [0, 1] (Texture.info.w, two bits per axis).
const uint WRAP_REPEAT = 0u;
const uint WRAP_CLAMP = 1u;
const uint WRAP_MIRROR = 2u;

// How a texture's texels are stored (Texture.info.w bits 4-5; texture.glsl).
const uint TEXEL_HALF = 0u;   // two words a texel: half floats (r, g), (b, a), linear
const uint TEXEL_RGBA8 = 1u;  // one word a texel: bytes r, g, b, a from the lowest
// Texture.info.w bit 6: an RGBA8 texture's r, g and b are sRGB-encoded, decoded
// through the table at the start of table_words (SRGB_TABLE_WORDS words, one float
// per byte value).
const uint TEXTURE_SRGB_BIT = 64u;
const uint SRGB_TABLE_WORDS = 256u;

// Mesa's lavapipe stops an invocation's loops silently after 65,535 iterations in
// total (docs/architecture.md). The kernel counts its own iterations the way lavapipe does
// (budget.glsl) against a budget below that cap, with room to spare.
const uint DEFAULT_LOOP_BUDGET = 60000u;

// Pending rays of the reflection/refraction tree (sample.glsl): one per generation
// is enough, so max_depth 8 never overflows the stack.
const uint RAY_STACK_SIZE = 8u;

// How a hemisphere direction is drawn (hemisphere.glsl).
const uint HEMISPHERE_ANGLES = 0u;   // the paper's Fig. 13: theta and phi uniform
const uint HEMISPHERE_UNIFORM = 1u;  // uniform in solid angle
const uint HEMISPHERE_COSINE = 2u;   // density proportional to cos(theta)

// Global mode's estimators (global.glsl), Params.global.x.
const uint ESTIMATOR_PAPER = 0u;
const uint ESTIMATOR_PATH = 1u;

// Where the random numbers come from (rng.glsl), render.sampler.
const uint SAMPLER_HASH = 0u;   // an independent hash per number
const uint SAMPLER_SOBOL = 1u;  // Owen-scrambled Sobol points, one shuffled 2-D set per slot

// The slots a path draws from (rng.glsl, global.glsl): the camera's and the lens's
// first, then from SLOT_PATH on BOUNCE_SLOTS per bounce in this order, so a decision
// always takes the same slot whichever branches the path took before it.
const uint SLOT_CAMERA = 0u;
const uint SLOT_LENS = 1u;
const uint SLOT_PATH = 2u;
const uint SLOT_LIGHT = 0u;  // offsets within a bounce's slots: the light's choice and its point
const uint SLOT_LOBE = 1u;
const uint SLOT_DIRECTION = 2u;
const uint SLOT_ROULETTE = 3u;
const uint BOUNCE_SLOTS = 4u;

const float INFINITY_T = 3.0e38f;   // "no hit yet"; finite so comparisons stay ordered

// Shadow rays stop this fraction short of their light, so that a light placed exactly
// on a surface (a lamp on the ceiling) is not shadowed by the surface it sits on,
// whose hit distance rounds to either side of the light's.
const float SHADOW_RAY_END = 0.9999f;

const float PI = 3.14159265358979f;
