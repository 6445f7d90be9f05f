// Ray-primitive intersection: pure functions of their arguments (no buffers), so the
// unit tests call them directly through the reference backend.

// a * b as hi + lo exactly: hi the rounded product, lo its rounding error (Dekker's
// product, splitting each factor into two 12-bit halves as Veltkamp does, so that the
// four partial products are exact without a fused multiply-add). `precise` keeps a
// compiler from simplifying (c - (c - a)) to a. 4097 * a must not overflow (|a| < 8e34).
vec2 exact_product(float a, float b) {
    const float SPLIT = 4097.0f;  // 2^12 + 1
    precise float ca = SPLIT * a;
    precise float a_hi = ca - (ca - a);
    precise float a_lo = a - a_hi;
    precise float cb = SPLIT * b;
    precise float b_hi = cb - (cb - b);
    precise float b_lo = b - b_hi;
    precise float hi = a * b;
    precise float lo = ((a_hi * b_hi - hi) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
    return vec2(hi, lo);
}

// a + b as hi + lo exactly (Knuth's two-sum).
vec2 exact_sum(float a, float b) {
    precise float s = a + b;
    precise float b_virtual = s - a;
    precise float lo = (a - (s - b_virtual)) + (b - b_virtual);
    return vec2(s, lo);
}

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
// defer the few spheres that need the exact one (traversal.glsl, DeferredSpheres).
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

// Result of a ray-triangle test: t (INFINITY_T for a miss) and the barycentric
// weights u of p1 and v of p2 (p0 gets 1 - u - v).
struct TriangleHit {
    float t;
    float u;
    float v;
};

// v's coordinates in the order (kx, ky, kz) = (kz + 1, kz + 2, kz) mod 3: a rotation,
// which keeps the sheared frame right-handed. Chosen by selects rather than by
// indexing v[k] with a run-time k, which both compilers turned into stores and loads
// through memory (the reference's brute force on SPD tetra ran at a quarter of
// Möller-Trumbore's speed with indexing).
vec3 permute_axes(vec3 v, int kz) {
    return kz == 0 ? vec3(v.y, v.z, v.x) : (kz == 1 ? vec3(v.z, v.x, v.y) : v);
}

// The axis along which `dir` is largest in magnitude: the sheared frame's z.
int dominant_axis(vec3 dir) {
    vec3 ad = abs(dir);
    return ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
}

// p's coordinates relative to the ray's origin, permuted so the ray runs along z and
// sheared so it runs along z exactly: the paper's x - (d.x / d.z) z, scaled by d.z so
// that no division is needed (the edge functions scale by d.z^2 > 0, which changes no
// sign and no ratio). `d` is the permuted direction.
vec2 sheared(vec3 p, Ray ray, vec3 d, int kz) {
    precise vec3 q = permute_axes(p - ray.origin, kz);
    precise float x = q.x * d.z - d.x * q.z;
    precise float y = q.y * d.z - d.y * q.z;
    return vec2(x, y);
}

// What the triangle and the quad tests share once the edge functions found the ray
// inside: the distance t from the plane through p0, p1, p2, and the weights u = ev /
// det, v = ew / det.
TriangleHit plane_hit(Ray ray, vec3 p0, vec3 p1, vec3 p2, float det, float ev, float ew, float t_min,
                      float t_max) {
    TriangleHit miss = TriangleHit(INFINITY_T, 0.0f, 0.0f);
    if (det == 0.0f) {
        return miss;
    }
    precise vec3 e1 = p1 - p0;
    precise vec3 e2 = p2 - p0;
    precise float nx = e1.y * e2.z - e1.z * e2.y;
    precise float ny = e1.z * e2.x - e1.x * e2.z;
    precise float nz = e1.x * e2.y - e1.y * e2.x;
    if (nx == 0.0f && ny == 0.0f && nz == 0.0f) {
        return miss;
    }
    // The distance from the plane through p0, not from the paper's barycentric sum
    // eu a.z + ev b.z + ew c.z: that sum cancels terms as large as the vertices'
    // distances along the dominant axis, and for a large triangle met far from its
    // corners (a 2e4-wide glass slab, a ray nearly along it) it put the hit point 1e-3
    // off the plane, beyond the offset that keeps the next ray on the right side. The
    // plane form errs by rounding of the normal's projection only (exactly nothing
    // for an axis-aligned plane). The edge functions still decide the hit.
    precise float n_dot_d = nx * ray.dir.x + ny * ray.dir.y + nz * ray.dir.z;
    if (n_dot_d == 0.0f) {
        return miss;
    }
    precise vec3 to_p0 = p0 - ray.origin;
    precise float t = (nx * to_p0.x + ny * to_p0.y + nz * to_p0.z) / n_dot_d;
    if (!(t > t_min && t < t_max)) {
        return miss;
    }
    precise float u = ev / det;
    precise float v = ew / det;
    return TriangleHit(t, u, v);
}

// Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection" (JCGT 2013). The
// vertices are moved to the ray's origin and sheared so that the ray runs along +-z
// (its dominant axis kz); the 2D edge functions U, V, W of the sheared triangle at
// (0, 0) then decide the hit. The paper precomputes the shear once per ray; this
// function gets the ray per test, so it scales the shear by d.z instead of dividing by
// it (no division before a hit is known).
// A vertex's sheared coordinates depend on the vertex and the ray only, never on the
// triangle, so two triangles sharing an edge compute that edge's function from the
// same numbers. Each edge function is a difference of two rounded products, and
// rounding is monotonic, so its computed sign is the exact sign for the sheared float
// vertices, or zero, never the opposite sign (with or without denormals flushed). The
// paper recomputes exact zeros in double; double is optional in GLSL, so here a zero
// counts as inside: the triangles accepted are a superset of the exactly hit ones, and
// a ray through a shared edge or vertex hits at least one of the triangles around it.
// The price: a ray within one rounding of an edge may hit the triangle beyond it too
// (at nearly the same t), or a silhouette triangle a rounding outside its edge. Every
// expression is precise: a fused multiply-add on one backend only would break both the
// sign argument and the identity of the two backends.
// Both faces are hit. A ray lying in the triangle's plane meets no inside: where the
// shear is exact (a plane x, y or z = c, or products that do not round) the sheared
// vertices lie on one line through the ray, all three functions are zero, det is 0
// and the ray misses; where the shear's products round they can open a sliver around
// that line, and a hit there is finite with barycentrics in [0, 1]. A triangle of zero
// area in float (its edge vectors' cross product exactly zero) is never hit: it has no
// normal to shade with, and its sheared image, rounded, could still be a sliver.
// Returns t and the barycentric weights u of p1 and v of p2, as Moller-Trumbore's
// test, which this one replaced, did.
TriangleHit intersect_triangle(Ray ray, vec3 p0, vec3 p1, vec3 p2, float t_min, float t_max) {
    TriangleHit miss = TriangleHit(INFINITY_T, 0.0f, 0.0f);
    int kz = dominant_axis(ray.dir);
    vec3 d = permute_axes(ray.dir, kz);
    vec2 a = sheared(p0, ray, d, kz);
    vec2 b = sheared(p1, ray, d, kz);
    vec2 c = sheared(p2, ray, d, kz);
    precise float eu = c.x * b.y - c.y * b.x;  // weight of p0
    precise float ev = a.x * c.y - a.y * c.x;  // weight of p1
    precise float ew = b.x * a.y - b.y * a.x;  // weight of p2
    if ((eu < 0.0f || ev < 0.0f || ew < 0.0f) && (eu > 0.0f || ev > 0.0f || ew > 0.0f)) {
        return miss;
    }
    precise float det = eu + ev + ew;
    return plane_hit(ray, p0, p1, p2, det, ev, ew, t_min, t_max);
}

// The same test for the quadrilateral p0, p1, p2, p3 (convex, planar, front face on
// the side of cross(p1 - p0, p2 - p0)): four edge functions instead of three, one
// test where the quad's two triangles took two, and no shared diagonal to rule on.
// The sum of the four is twice the sheared quad's signed area (the shoelace formula),
// as the triangle's three sum to twice its own. With p3 = p2 the fourth edge function
// is exactly 0 and the result is intersect_triangle's, bit for bit. For a
// parallelogram p0, p0 + e1, p0 + e1 + e2, p0 + e2 the edge functions of opposite
// edges sum to half of det, so u and v are half the hit's coordinates along e1 and e2.
TriangleHit intersect_quad(Ray ray, vec3 p0, vec3 p1, vec3 p2, vec3 p3, float t_min, float t_max) {
    TriangleHit miss = TriangleHit(INFINITY_T, 0.0f, 0.0f);
    int kz = dominant_axis(ray.dir);
    vec3 d = permute_axes(ray.dir, kz);
    vec2 a = sheared(p0, ray, d, kz);
    vec2 b = sheared(p1, ray, d, kz);
    vec2 c = sheared(p2, ray, d, kz);
    vec2 e = sheared(p3, ray, d, kz);
    precise float eu = c.x * b.y - c.y * b.x;  // edge p1 p2
    precise float ev = a.x * e.y - a.y * e.x;  // edge p3 p0
    precise float ew = b.x * a.y - b.y * a.x;  // edge p0 p1
    precise float ex = e.x * c.y - e.y * c.x;  // edge p2 p3
    if ((eu < 0.0f || ev < 0.0f || ew < 0.0f || ex < 0.0f) && (eu > 0.0f || ev > 0.0f || ew > 0.0f || ex > 0.0f)) {
        return miss;
    }
    precise float det = eu + ev + ew + ex;
    return plane_hit(ray, p0, p1, p2, det, ev, ew, t_min, t_max);
}

// Unit geometric normal of a triangle, on its front side (cross(p1 - p0, p2 - p0)).
vec3 triangle_face_normal(vec3 p0, vec3 p1, vec3 p2) {
    return unit_vector(cross(p1 - p0, p2 - p0));
}

// Vertex normals blended with the barycentric weights (the paper's Fig. 9).
// A blend that is zero or not finite (opposing or broken normals) falls back to the
// face normal instead of producing NaN.
vec3 interpolate_normal(vec3 n0, vec3 n1, vec3 n2, float u, float v, vec3 face_normal) {
    vec3 n = (1.0f - u - v) * n0 + u * n1 + v * n2;
    float len2 = dot(n, n);
    if (!(len2 > 1.0e-20f && len2 < 1.0e30f)) {
        return face_normal;
    }
    return n / sqrt(len2);
}

// Nearest t in (t_min, t_max) where the ray meets the ring (annulus) around `center`
// in the plane perpendicular to `normal`, or INFINITY_T. Both faces are hit; a ray
// parallel to the plane misses (denominator exactly 0), even one lying in it. The
// ring is closed: points exactly at the inner or outer radius count. The radius test
// compares squared distances, so no square root is taken.
float intersect_ring(Ray ray, vec3 center, vec3 normal, float inner, float outer, float t_min, float t_max) {
    float denom = dot(normal, ray.dir);
    if (denom == 0.0f) {
        return INFINITY_T;
    }
    precise float t = dot(center - ray.origin, normal) / denom;
    if (!(t > t_min && t < t_max)) {
        return INFINITY_T;
    }
    precise vec3 d = ray.origin + t * ray.dir - center;
    precise float d2 = dot(d, d);
    if (!(d2 >= inner * inner && d2 <= outer * outer)) {
        return INFINITY_T;
    }
    return t;
}

// Result of a ray-cylinder test: t (INFINITY_T for a miss) and the part hit
// (CYLINDER_SIDE, CYLINDER_BASE_CAP or CYLINDER_TOP_CAP, constants.glsl).
struct CylinderHit {
    float t;
    uint part;
};

// Nearest t in (t_min, t_max) where the ray meets the cylinder of `radius` around the
// segment base -> top: its side, and with `capped` the discs closing its two ends.
// `dir` must be unit length.
//
// In the frame of the axis a (unit), with o = origin - base, the side is where the
// part of o + t dir across the axis has length radius:
//   |o_perp + t d_perp|^2 = radius^2,   o_perp = o - (o.a) a,  d_perp = dir - (dir.a) a,
// a quadratic A t^2 + 2 B t + C = 0 with A = |d_perp|^2, B = o_perp.d_perp,
// C = |o_perp|^2 - radius^2. As in intersect_sphere, the discriminant B^2 - AC is
// computed as A (radius^2 - |f|^2), f = o_perp - (B / A) d_perp being the ray's point
// of closest approach to the axis (seen along it), and the second root as C / q, so
// neither cancels catastrophically. Both roots are tried, nearest first, each kept only
// where its height h = o.a + t dir.a lies on the segment, 0 <= h <= |top - base|: so a
// ray from inside an open cylinder hits the far wall. A ray parallel to the axis (A = 0)
// never meets the side. A ray tangent to the side (discriminant 0) touches it at the
// double root; a ray in the plane of an end circle hits the side there (h = 0 or h =
// |top - base| counts: the segment is closed). Caps are discs (radius included) in the
// planes h = 0 and h = |top - base|.
CylinderHit intersect_cylinder(Ray ray, vec3 base, vec3 top, float radius, bool capped, float t_min,
                               float t_max) {
    CylinderHit hit = CylinderHit(INFINITY_T, CYLINDER_SIDE);
    vec3 axis = top - base;
    float len = length(axis);
    if (!(len > 0.0f)) {
        return hit;
    }
    axis = axis / len;
    vec3 o = ray.origin - base;
    float oa = dot(o, axis);
    float da = dot(ray.dir, axis);
    precise vec3 o_perp = o - oa * axis;
    precise vec3 d_perp = ray.dir - da * axis;
    float r2 = radius * radius;
    float a = dot(d_perp, d_perp);
    float bound = t_max;
    if (a > 0.0f) {
        float b = dot(o_perp, d_perp);
        precise vec3 f = o_perp - (b / a) * d_perp;
        // precise, as in intersect_sphere: these decide rim and grazing hits, and a
        // fused multiply-add on one backend only would move them.
        precise float disc = r2 - dot(f, f);
        if (disc >= 0.0f) {
            precise float c = dot(o_perp, o_perp) - r2;
            precise float root = sqrt(a * disc);
            precise float q = b >= 0.0f ? -(b + root) : root - b;
            precise float t_a = q / a;
            precise float t_b = q != 0.0f ? c / q : 0.0f;
            float t_near = min(t_a, t_b);
            float t_far = max(t_a, t_b);
            precise float h_near = oa + t_near * da;
            precise float h_far = oa + t_far * da;
            if (t_near > t_min && t_near < t_max && h_near >= 0.0f && h_near <= len) {
                hit.t = t_near;
            } else if (t_far > t_min && t_far < t_max && h_far >= 0.0f && h_far <= len) {
                hit.t = t_far;
            }
            bound = min(bound, hit.t);
        }
    }
    if (capped && da != 0.0f) {
        precise float t_base = -oa / da;
        precise vec3 e_base = o_perp + t_base * d_perp;
        if (t_base > t_min && t_base < bound && dot(e_base, e_base) <= r2) {
            hit = CylinderHit(t_base, CYLINDER_BASE_CAP);
            bound = t_base;
        }
        precise float t_top = (len - oa) / da;
        precise vec3 e_top = o_perp + t_top * d_perp;
        if (t_top > t_min && t_top < bound && dot(e_top, e_top) <= r2) {
            hit = CylinderHit(t_top, CYLINDER_TOP_CAP);
        }
    }
    return hit;
}

// Unit geometric normal of a cylinder at point p of the given part, on its front
// (outer) side: away from the axis on the side, -axis on the base cap, +axis on the
// top cap.
vec3 cylinder_normal(vec3 base, vec3 top, vec3 p, uint part) {
    vec3 axis = unit_vector(top - base);
    if (part == CYLINDER_BASE_CAP) {
        return -axis;
    }
    if (part == CYLINDER_TOP_CAP) {
        return axis;
    }
    vec3 o = p - base;
    precise vec3 radial = o - dot(o, axis) * axis;
    return unit_vector(radial);
}
