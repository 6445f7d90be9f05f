// The sphere (Sphere, its record below): a centre and a radius. Its intersection, in a
// rounded form and an error-free one; its tests for the traversal; its hit record;
// and the points drawn on it when it emits, through the cone it fills as seen from
// the point lit (solid_angle.glsl) or uniformly by area. The contract this file
// fulfils is in shapes/kinds.glsl.

#ifdef SHAPE_RECORDS  // the record, which layout.glsl includes

// A sphere: centre in xyz, radius in w; meta.x = material index.
struct Sphere {
    vec4 center_radius;
    uvec4 meta;
};
#define Sphere_FROM_TEXELS(b, i) Sphere(fetch_vec4(b, 2u * (i)), fetch_texel(b, 2u * (i) + 1u))

#else  // the rest, which all.glsl includes

// ---------------------------------------------------------------- intersection

// |origin - center|^2 - r^2 with every difference, product and sum error-free and
// their errors added at the end (a compensated sum, Ogita, Rump & Oishi's Sum2): about
// as exact as if it were computed in double and rounded once, however much the terms
// cancel. The difference origin - center is kept as hi + lo too: a shadow ray leaving
// a sphere of radius 1e5 starts 3e-5 above it, less than the ULP (0.0078) of the
// rounded difference.
float sphere_c_exact(vec3 origin, vec3 center, float r) {
    vec2 dx = exact_sum(origin.x, -center.x);
    vec2 dy = exact_sum(origin.y, -center.y);
    vec2 dz = exact_sum(origin.z, -center.z);
    vec2 x = exact_product(dx.x, dx.x);
    vec2 y = exact_product(dy.x, dy.x);
    vec2 z = exact_product(dz.x, dz.x);
    vec2 rr = exact_product(r, r);
    vec2 s = exact_sum(x.x, y.x);
    precise float err = (x.y + y.y) + s.y;
    s = exact_sum(s.x, z.x);
    err = err + (z.y + s.y);
    s = exact_sum(s.x, -rr.x);
    err = err + (s.y - rr.y);
    // (hi + lo)^2 = hi^2 + 2 hi lo + lo^2: the terms of the differences' low parts.
    precise float low = 2.0f * ((dx.x * dx.y + dy.x * dy.y) + dz.x * dz.y) +
                        ((dx.y * dx.y + dy.y * dy.y) + dz.y * dz.y);
    precise float result = s.x + (err + low);
    return result;
}

// What both forms of the sphere test below share: the ray's origin relative to the
// centre, b = oc . dir, r^2, |oc|^2 and c = |oc|^2 - r^2 as rounded.
struct SphereSetup {
    vec3 oc;
    float b;
    float r2;
    float oo;
    float c;
};

SphereSetup sphere_setup(Ray ray, vec3 center, float radius) {
    vec3 oc = ray.origin - center;
    // precise here: the values b feeds are precise, but in the callers, and glslang
    // marks an expression's operands NoContraction within one function only.
    precise float b = dot(oc, ray.dir);
    float r2 = radius * radius;
    precise float oo = dot(oc, oc);
    precise float c = oo - r2;
    return SphereSetup(oc, b, r2, oo, c);
}

// True where the rounded c cancels: |c| under half of |oc|^2, an origin between
// 0.82 r and 1.41 r from the centre, such as a point on the sphere itself. There the
// test needs the error-free c (sphere_exact_c_test); elsewhere c loses under a bit.
bool sphere_needs_exact_c(SphereSetup s) {
    return abs(s.c) < 0.5f * s.oo;
}

// The nearer root in (t_min, t_max) of t^2 + 2 b t + c = 0 given its discriminant,
// or INFINITY_T: the first root from q, the second from c / q, which do not cancel.
float sphere_roots(float b, float c, float disc, float t_min, float t_max) {
    if (!(disc >= 0.0f)) {
        return INFINITY_T;
    }
    float root = sqrt(disc);
    precise float q = b >= 0.0f ? -(b + root) : root - b;
    float t_a = q;
    precise float t_b = q != 0.0f ? c / q : 0.0f;
    float t_near = min(t_a, t_b);
    float t_far = max(t_a, t_b);
    if (t_near > t_min && t_near < t_max) {
        return t_near;
    }
    if (t_far > t_min && t_far < t_max) {
        return t_far;
    }
    return INFINITY_T;
}

// The discriminant from the distance between the centre and the ray's closest point,
// r^2 - |f|^2, which does not cancel for distant spheres as b^2 - c does.
float sphere_closest_point_disc(Ray ray, SphereSetup s) {
    precise vec3 f = s.oc - s.b * ray.dir;
    precise float disc = s.r2 - dot(f, f);
    return disc;
}

// The sphere test where c does not cancel (!sphere_needs_exact_c).
float sphere_rounded_c_test(Ray ray, SphereSetup s, float t_min, float t_max) {
    return sphere_roots(s.b, s.c, sphere_closest_point_disc(ray, s), t_min, t_max);
}

// The sphere test where c cancels (sphere_needs_exact_c): c error-free, and the
// discriminant b^2 - c from it and an exact b^2.
float sphere_exact_c_test(Ray ray, vec3 center, float radius, SphereSetup s, float t_min, float t_max) {
    precise float c = sphere_c_exact(ray.origin, center, radius);
    vec2 bb = exact_product(s.b, s.b);
    precise float disc = (bb.x - c) + bb.y;
    return sphere_roots(s.b, c, disc, t_min, t_max);
}

// Nearest t in (t_min, t_max) where the ray meets the sphere, or INFINITY_T.
// Uses the form of the quadratic that does not cancel catastrophically (Haines et
// al., "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7):
// the discriminant comes from the distance between the centre and the ray's closest
// point rather than from b^2 - c, and the second root from c / q.
// `dir` must be unit length.
//
// c = |oc|^2 - r^2 still cancels where the origin lies near the surface compared with
// the radius: 1.5 above a sphere of radius 1e5 it is 3e5 out of 1e10, where a float's
// ULP is 1024, so the near root c / q was 0.3% off, eye rays' hit points landed inside
// the ground, and shadow rays leaving it found themselves inside it: the ground
// shadowed itself (tests/stability/scale_test.cpp). Where |c| is under half of
// |oc|^2, c is therefore computed error-free (sphere_c_exact); elsewhere it loses
// under a bit, and the cheap form stays (the overflow guard comes free: an infinite
// |oc|^2 fails the test). There the discriminant is b^2 - c from the exact c and an
// exact b^2, whose error, 2 b times b's rounding, is at most that of r^2 - |f|^2 (2 r
// times f's) and far below it for rays near the horizon (b << r), where r^2 - |f|^2
// lost the root and put hit points up to 1e-2 under the ground.
//
// SIMD hardware that runs both sides of a branch (lavapipe) pays for the error-free
// form on every test; loops over many spheres therefore call the two forms apart and
// defer the few spheres that need the exact one (deferred_spheres.glsl).
float intersect_sphere(Ray ray, vec3 center, float radius, float t_min, float t_max) {
    SphereSetup s = sphere_setup(ray, center, radius);
    if (sphere_needs_exact_c(s)) {
        return sphere_exact_c_test(ray, center, radius, s, t_min, t_max);
    }
    return sphere_rounded_c_test(ray, s, t_min, t_max);
}

// How close to the surface, relative to |oc|^2, a ray's origin may lie before the
// rounded c stops deciding which side of it the origin is on: c's rounding error is
// at most about 6 * 2^-24 |oc|^2 (oc's three rounded differences, the three squares,
// their two sums, r^2 and the last difference), so outside 2^-18 |oc|^2 the rounded c
// has the exact c's sign with a margin of ten. Within it the origin counts as on the
// surface (sphere_blocks).
const float SPHERE_C_SIGN_MARGIN = 3.814697265625e-06f;   // 2^-18

// Whether the ray meets the sphere at some t in (0, t_max): the question a shadow ray
// asks, which needs neither the roots' values nor, mostly, an exact c.
// Where the roots lie comes from their product c and sum -2b: with the discriminant
// non-negative, the nearer root t0 is positive when c > 0 and b < 0 (the origin is
// outside and the ray heads toward the centre), the farther t1 when c < 0 or b < 0.
// Only their comparisons with t_max need the roots themselves, -b -+ sqrt(disc): each
// cancels only where it is tiny, and is then far below t_max unless the light lies
// within a rounding of the ray's origin; a shadow ray stops short of its light anyway
// (SHADOW_RAY_END).
// So c matters only for its sign, which the rounded c gets right unless the origin
// lies within SPHERE_C_SIGN_MARGIN of the surface; such an origin, a shadow ray
// leaving the sphere it starts on, counts as on the surface (c = 0): a ray leaving the
// surface is not blocked by it, a ray entering it is (t1 = -2b). The error-free c
// would say the same wherever the origin lies outside, as offset_ray_origin puts it,
// and would let a hit point that rounded to inside block its own shadow ray.
// The discriminant is sphere_closest_point_disc, as in the rounded-c test; its error
// moves the decision only for rays tangent to the sphere within a rounding.
// Compared with intersect_sphere(ray, ..., 0, t_max) != INFINITY_T, which it equals
// away from those margins, it skips the error-free c, which SIMD hardware computes on
// every test (both sides of the branch), and the division for the second root
// (docs/decisions/0006-shadow-rays-sphere-blocks.md).
bool sphere_blocks(Ray ray, vec3 center, float radius, float t_max) {
    SphereSetup s = sphere_setup(ray, center, radius);
    float disc = sphere_closest_point_disc(ray, s);
    float c = abs(s.c) < SPHERE_C_SIGN_MARGIN * s.oo ? 0.0f : s.c;
    float h = sqrt(max(disc, 0.0f));
    precise float t0 = -s.b - h;
    precise float t1 = h - s.b;
    bool near_root = c > 0.0f && s.b < 0.0f && t0 < t_max;
    bool far_root = (c < 0.0f || s.b < 0.0f) && t1 < t_max;
    return disc >= 0.0f && (near_root || far_root);
}

// ---------------------------------------------------------------- traversal

void set_sphere_nearest(uint index, float t, INOUT(Nearest) nearest) {
    if (t < nearest.t) {
        nearest.t = t;
        nearest.ref = (REF_SPHERE << REF_KIND_SHIFT) | index;
    }
}

// A closest-hit ray's sphere test: where it first meets the sphere.
void test_sphere_closest(Ray ray, uint index, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    vec4 s = load_sphere(index).center_radius;
    set_sphere_nearest(index, intersect_sphere(ray, vec3(s), s.w, 0.0f, nearest.t), nearest);
}

// A shadow ray's sphere test: whether the sphere blocks it, not where (sphere_blocks).
// A blocker sets only the reference; the trace ends there.
void test_sphere_blocks(Ray ray, uint index, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    vec4 s = load_sphere(index).center_radius;
    if (sphere_blocks(ray, vec3(s), s.w, nearest.t)) {
        nearest.ref = (REF_SPHERE << REF_KIND_SHIFT) | index;
    }
}

// The sphere test for the ray's question: where it first meets the sphere, or, with
// any_hit, whether it meets it at all. The sphere is read inside each test: read by the
// caller and passed in, the CPU backend's sphere loops ran up to 1.1x slower.
void test_sphere(Ray ray, uint index, bool any_hit, INOUT(Nearest) nearest) {
    if (any_hit) {
        test_sphere_blocks(ray, index, nearest);
    } else {
        test_sphere_closest(ray, index, nearest);
    }
}

Hit sphere_hit(Ray ray, uint index, Nearest nearest) {
    Sphere s = load_sphere(index);
    vec3 center = vec3(s.center_radius);
    precise vec3 p = ray.origin + nearest.t * ray.dir;
    // Normalized, not divided by the radius: far from the origin p carries the
    // rounding of its magnitude, and (p - c) / r drifts off unit length.
    vec3 n = unit_vector(p - center);
    bool front = dot(n, ray.dir) < 0.0f;
    vec3 facing = front ? n : -n;
    return Hit(nearest.t, facing, facing, vec3(0.0f), s.meta.x, front, (REF_SPHERE << REF_KIND_SHIFT) | index,
               vec2(0.0f), vec2(0.0f));
}

// ---------------------------------------------------------------- emission

float sphere_area(float radius) {
    return 4.0f * PI * radius * radius;
}

// A direction uniform over the unit sphere: z uniform in [-1, 1] (Archimedes' hat-box
// theorem: equal heights cut equal areas), the angle around z uniform.
vec3 uniform_sphere_direction(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float s = sqrt(max(0.0f, 1.0f - z * z));
    float phi = (2.0f * PI) * u2;
    vec2 sc = sin_cos(phi);
    return vec3(s * sc.y, s * sc.x, z);
}

float sphere_pick_weight(uint, Material m) {
    return emission_weight(m.emission);
}

EmitterPoint sphere_emitter_point(uint index, uint, float u1, float u2) {
    Sphere s = load_sphere(index);
    vec3 n = uniform_sphere_direction(u1, u2);
    precise vec3 y = vec3(s.center_radius) + s.center_radius.w * n;
    vec3 emission = load_material(s.meta.x).emission;
    return EmitterPoint(y, n, emission, emission_weight(emission));
}

// Through the cone the sphere fills as seen from o, where its solid angle allows.
bool sphere_light_sample(vec3 o, uint index, vec2 u, INOUT(LightSample) drawn) {
    Sphere s = load_sphere(index);
    vec3 center = vec3(s.center_radius);
    SphereCone cone = sphere_cone(o, center, s.center_radius.w);
    float omega = sphere_cone_solid_angle(cone);
    if (!sampled_by_solid_angle(omega)) {
        return false;
    }
    vec3 y = sphere_cone_point(o, cone, s.center_radius.w, u.x, u.y);
    vec3 emission = load_material(s.meta.x).emission;
    float choice = emission_weight(emission) * sphere_area(s.center_radius.w) / emitter_power();
    drawn = LightSample(y, unit_vector(y - center), emission, choice / omega);
    return true;
}

bool sphere_light_pdf(vec3 o, uint index, float area_density, INOUT(float) pdf) {
    Sphere s = load_sphere(index);
    float radius = s.center_radius.w;
    float omega = sphere_cone_solid_angle(sphere_cone(o, vec3(s.center_radius), radius));
    if (!sampled_by_solid_angle(omega)) {
        return false;
    }
    pdf = area_density * sphere_area(radius) / omega;
    return true;
}

#endif  // SHAPE_RECORDS
