// Buffer layouts shared by the compute shader and the C++ host.
// vec4/uvec4 members only, so GLSL and C++ agree on every offset without padding
// rules to remember (std140 and std430 coincide for such structs), and each member is
// one 16-byte texel of the texel buffers render.comp reads them from;
// host/kernel_types.hpp static_asserts the sizes.
// Unused .w lanes are documented as such and written as 0 by the host.

// A sphere: centre in xyz, radius in w; meta.x = material index.
struct Sphere {
    vec4 center_radius;
    uvec4 meta;
};

// A triangle stores its own vertices (no index indirection: one fetch per primitive).
// Vertex normals are used only when meta.y != 0 (the scene gave normals); the front
// face is the side of cross(p1 - p0, p2 - p0). meta.x = material index.
struct Triangle {
    vec4 p0;
    vec4 p1;
    vec4 p2;
    vec4 n0;
    vec4 n1;
    vec4 n2;
    uvec4 meta;
};

// A ring (annulus) in the plane through `center` perpendicular to `normal`: the points
// whose distance from the centre lies in [inner, outer] (inner 0: a disc). The normal
// is unit length (the loader normalizes it) and marks the front face. meta.x =
// material index.
struct Ring {
    vec4 center_inner;  // xyz centre, w inner radius
    vec4 normal_outer;  // xyz unit normal (front side), w outer radius
    uvec4 meta;
};

// A cylinder around the segment from `base` to `top`: the side, and with capped != 0
// the two end discs. The ends are stored rather than an axis and a length, so the host
// bounds it from the very floats the kernel intersects, and the kernel derives the unit
// axis per test (one square root). The outside is the front face. meta.x = material
// index.
struct Cylinder {
    vec4 base_radius;  // xyz centre of the base disc, w radius
    vec4 top_capped;   // xyz centre of the top disc, w = 1 capped, 0 open
    uvec4 meta;
};

// Material fields as in the scene file (docs/scene-format.md).
struct Material {
    vec4 diffuse_kd;         // rgb diffuse colour, w = kd
    vec4 specular_ks;        // rgb specular colour, w = ks
    vec4 reflect_shininess;  // rgb mirror reflectance, w = Phong exponent
    vec4 transmit_ior;       // rgb transmittance, w = index of refraction
    vec4 emission_fresnel;   // rgb emitted radiance (front face only), w = 1: Fresnel-weighted
                             // reflection/refraction, 0: the constant weights reflect and transmit
};

// A point light: position in xyz; rgb = colour * intensity.
struct PointLight {
    vec4 position;
    vec4 radiance;
};

// One emissive primitive: a primitive whose material has nonzero emission
// (kernel/emitters.glsl samples them, host/scene/scene_gpu.cpp lists them). Emitters
// are chosen with probability proportional to their area, through the cumulative
// fractions in cdf_area.x, the last of which is exactly 1.
struct Emitter {
    uvec4 prim;      // x = primitive reference (kind << REF_KIND_SHIFT | index, as the grid's),
                     // y = the part of a cylinder (CYLINDER_SIDE, _BASE_CAP, _TOP_CAP), z/w unused
    vec4 cdf_area;   // x = area of the emitters up to and including this one / total area, y = area, z/w unused
};

// Per-render constants. The camera is given as direction vectors relative to the eye:
// the ray through continuous image position (x, y), in pixels from the top-left
// corner, has direction cam_corner + x * cam_right + y * cam_down.
struct Params {
    vec4 cam_eye;
    vec4 cam_corner;
    vec4 cam_right;
    vec4 cam_down;
    vec4 ambient;      // rgb ambient light, w unused
    vec4 background;   // rgb radiance of rays that hit nothing, w unused
    uvec4 image;       // x width, y height, z aa (sub-pixels per side), w seed
    uvec4 counts;      // x spheres, y triangles, z point lights, w materials
    uvec4 limits;      // x loop-iteration budget per invocation, y max_depth (reflection and
                       // refraction generations after the eye ray), z/w unused
    // The uniform grid (kernel/grid.glsl, host/accel/grid.cpp), when HAS_GRID: cell
    // (i, j, k) spans grid_min + (i, j, k) * grid_cell to grid_min + (i+1, j+1, k+1) *
    // grid_cell. grid_max is the box the rays are clipped to.
    vec4 grid_min;       // xyz, w unused
    vec4 grid_max;       // xyz, w unused
    vec4 grid_cell;      // xyz cell size, w unused
    vec4 grid_inv_cell;  // xyz 1 / cell size, w unused
    uvec4 grid_res;      // xyz cells per axis, w unused
    // Counts of the primitive kinds that came after `counts` was full.
    uvec4 more_counts;   // x rings, y cylinders, z/w unused
    // The reflection/refraction tree (sample.glsl): x the weight below which a
    // secondary ray is dropped (0: never), yzw unused.
    vec4 ray_tree;
    // Area lights (kernel/area_lights.glsl), when HAS_AREA_LIGHTS: the Emitter list
    // and the shadow rays each hit sends toward it.
    uvec4 area_lights;   // x emitters, y light samples per hit, z/w unused
    vec4 emitter_area;   // x total area of the emitters, y/z/w unused
    // Global mode (global.glsl), when HAS_GLOBAL: x estimator (ESTIMATOR_*), y the
    // hemisphere rule (HEMISPHERE_*), z unused, w max_bounces.
    uvec4 global;
};

// Per-pixel sums of sample radiance (sums.glsl): each channel's exact sum as a 96-bit
// fixed-point integer in xyz, least significant word first, in units of 2^-40.
// red.w = samples summed, green.w = of those, samples clamped to SUM_SAMPLE_MAX,
// blue.w unused (0).
struct PixelSum {
    uvec4 red;
    uvec4 green;
    uvec4 blue;
};

// Per-pixel counters, lanes named in constants.glsl (RAYS_*, WORK_*).
struct Counters {
    uvec4 rays;
    uvec4 work;
    uvec4 tree;
    uvec4 paths;
};
