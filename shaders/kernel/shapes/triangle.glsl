// The triangle (Triangle, its record below), and the parallelogram that shares its record
// (meta.z != SHAPE_TRIANGLE, decision 0022): the watertight intersection, the test
// for the traversal, the hit record with its shading normal, terminator lift and
// texture coordinates, and the points drawn on it when it emits: through a
// rectangle's spherical rectangle (solid_angle.glsl) where that pays, else uniformly
// by area. The contract this file fulfils is in shapes/kinds.glsl.

#ifdef SHAPE_RECORDS  // the record, which layout.glsl includes

// A triangle stores its own vertices (no index indirection: one fetch per primitive).
// Vertex normals are used only when meta.y has TRIANGLE_NORMALS (the scene gave
// normals); TRIANGLE_ALPHA_TESTED there marks a material that is not opaque
// (alpha.glsl). The front face is the side of cross(p1 - p0, p2 - p0). meta.x =
// material index; meta.z =
// SHAPE_TRIANGLE, or SHAPE_PARALLELOGRAM / SHAPE_RECTANGLE for the parallelogram p0,
// p1, p2, p0 + p2 - p1 (constants.glsl), which has no vertex normals. The texture
// coordinates of p0, p1, p2 ride in the w lanes: (p0.w, p1.w), (p2.w, n0.w), (n1.w, n2.w).
// meta.w: with an emission texture, the float bits of the triangle's emitter weight
// (shapes/triangle.glsl, triangle_emitter_weight): the mean textured emission over its
// footprint in the texture, 0 where the footprint is black; 0 otherwise.
struct Triangle {
    vec4 p0;
    vec4 p1;
    vec4 p2;
    vec4 n0;
    vec4 n1;
    vec4 n2;
    uvec4 meta;
};
#define Triangle_FROM_TEXELS(b, i)                                                                      \
    Triangle(fetch_vec4(b, 7u * (i)), fetch_vec4(b, 7u * (i) + 1u), fetch_vec4(b, 7u * (i) + 2u),        \
             fetch_vec4(b, 7u * (i) + 3u), fetch_vec4(b, 7u * (i) + 4u), fetch_vec4(b, 7u * (i) + 5u),   \
             fetch_texel(b, 7u * (i) + 6u))

#else  // the rest, which all.glsl includes

// ---------------------------------------------------------------- intersection

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

// ---------------------------------------------------------------- traversal

// The texture coordinates at a hit of weights u (of p1) and v (of p2), as
// uv_at_weights (vertex_data.glsl) interpolates them.
vec2 triangle_uv(Triangle tri, float u, float v) {
    return uv_at_weights(triangle_uv_corner(tri, 0u), triangle_uv_corner(tri, 1u), triangle_uv_corner(tri, 2u),
                         HAS_QUADS && tri.meta.z != SHAPE_TRIANGLE, u, v);
}

// A hit on a triangle whose material is not opaque counts only where the surface is
// there (alpha.glsl).
void test_triangle(Ray ray, uint index, bool, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    Triangle tri = load_triangle(index);
    vec3 p0 = vec3(tri.p0);
    vec3 p1 = vec3(tri.p1);
    vec3 p2 = vec3(tri.p2);
    TriangleHit th;
    if (HAS_QUADS) {
        // One test for both shapes, the fourth vertex picked by a select: SIMD
        // hardware would run both tests on a branch.
        precise vec3 p3 = tri.meta.z == SHAPE_TRIANGLE ? p2 : p0 + (p2 - p1);
        th = intersect_quad(ray, p0, p1, p2, p3, 0.0f, nearest.t);
    } else {
        th = intersect_triangle(ray, p0, p1, p2, 0.0f, nearest.t);
    }
    bool tested = HAS_ALPHA && (tri.meta.y & TRIANGLE_ALPHA_TESTED) != 0u;
    if (th.t < nearest.t && (!tested || alpha_stops_ray(tri, index, vec2(th.u, th.v), triangle_uv(tri, th.u, th.v)))) {
        nearest.t = th.t;
        nearest.ref = (REF_TRIANGLE << REF_KIND_SHIFT) | index;
        nearest.uv = vec2(th.u, th.v);
    }
}

Hit triangle_hit(Ray ray, uint index, Nearest nearest) {
    Triangle tri = load_triangle(index);
    float u = nearest.uv.x;
    float v = nearest.uv.y;
    vec3 ng = triangle_face_normal(vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
    vec3 ns = ng;
    if (HAS_SMOOTH_NORMALS && (tri.meta.y & TRIANGLE_NORMALS) != 0u) {
        ns = interpolate_normal(vec3(tri.n0), vec3(tri.n1), vec3(tri.n2), u, v, ng);
    }
    bool front = dot(ng, ray.dir) < 0.0f;
    vec3 g = front ? ng : -ng;
    // The shading normal must lie on the viewer's side of the surface too.
    bool flip = dot(ns, g) < 0.0f;
    note_decision(flip ? DECISION_NORMAL_FLIPPED : DECISION_NORMAL_KEPT);
    vec3 s = flip ? -ns : ns;
    vec3 lift = vec3(0.0f);
    if (HAS_TERMINATOR && (tri.meta.y & TRIANGLE_NORMALS) != 0u) {
        lift = terminator_lift(tri, u, v, flip ? -1.0f : 1.0f, g);
    }
    vec2 uv = vec2(0.0f);
    if (HAS_TEXTURES) {
        uv = triangle_uv(tri, u, v);
    }
    return Hit(nearest.t, s, g, lift, tri.meta.x, front, (REF_TRIANGLE << REF_KIND_SHIFT) | index, uv, nearest.uv);
}

// ---------------------------------------------------------------- emission

// The weight by which a triangle or quad of material m is picked, as the host
// weighs its power (flat_scene.cpp): its emission's, or with an emission texture
// the mean textured emission over its footprint, which the host stores in the record.
// Light samples' densities are built on it, never on the textured radiance at a
// point, so that sample_light and light_pdf_of_hit give one point one density.
float triangle_emitter_weight(Material m, Triangle tri) {
    return HAS_TEXTURES && m.emission_map != 0u ? uintBitsToFloat(tri.meta.w) : emission_weight(m.emission);
}

// The same weight, the record read only where the material has an emission texture.
float triangle_pick_weight(uint index, Material m) {
    if (HAS_TEXTURES && m.emission_map != 0u) {
        return uintBitsToFloat(load_triangle(index).meta.w);
    }
    return emission_weight(m.emission);
}

// The radiance a triangle or quad of material m emits at the point of weights
// (u, v) (triangle_uv): its emission, times its emission texture there, and where
// its material is not opaque, times its coverage there (alpha.glsl).
vec3 triangle_emission(Material m, Triangle tri, uint index, float u, float v) {
    vec3 emission = m.emission;
    if (HAS_TEXTURES && m.emission_map != 0u) {
        emission = textured_emission(m, slot_uv(m, texture_coords(m, index, vec2(u, v), triangle_uv(tri, u, v)), MAP_EMISSION));
    }
    if (HAS_ALPHA && (tri.meta.y & TRIANGLE_ALPHA_TESTED) != 0u) {
        emission *= surface_coverage(m, triangle_uv(tri, u, v), vertex_alpha(tri, index, vec2(u, v)));
    }
    return emission;
}

// A parallelogram Triangle record (meta.z != SHAPE_TRIANGLE) as a corner and its two
// edges, perpendicular for SHAPE_RECTANGLE: p0, p0 + ex, p0 + ex + ey, p0 + ey.
struct Rect {
    vec3 corner;
    vec3 ex;
    vec3 ey;
};

Rect rect_of(Triangle tri) {
    return Rect(vec3(tri.p0), vec3(tri.p1) - vec3(tri.p0), vec3(tri.p2) - vec3(tri.p1));
}

float rect_area(Rect q) {
    return sqrt(dot(q.ex, q.ex) * dot(q.ey, q.ey));
}

// Whether o is near enough to the rectangle for its spherical rectangle to pay:
// within RECT_NEAR diagonals of its centre. Farther, distance and cosine vary little
// over the rectangle, area sampling is almost as good, and it costs a fraction of
// the spherical rectangle's square roots and arc tangents.
bool near_rect(vec3 o, Rect q) {
    vec3 d = q.corner + 0.5f * (q.ex + q.ey) - o;
    return dot(d, d) < RECT_NEAR * RECT_NEAR * (dot(q.ex, q.ex) + dot(q.ey, q.ey));
}

// Whether the rectangle is sampled by solid angle from o, and then its spherical
// rectangle: the one rule of triangle_light_sample and triangle_light_pdf.
bool rect_by_solid_angle(vec3 o, Rect q, INOUT(SphericalRect) sr) {
    if (!near_rect(o, q)) {
        return false;
    }
    sr = spherical_rect(o, q.corner, q.ex, q.ey);
    return sampled_by_solid_angle(sr.solid_angle);
}

EmitterPoint triangle_emitter_point(uint index, uint, float u1, float u2) {
    Triangle tri = load_triangle(index);
    vec3 p0 = vec3(tri.p0);
    vec3 p1 = vec3(tri.p1);
    vec3 p2 = vec3(tri.p2);
    Material m = load_material(tri.meta.x);
    float weight = triangle_emitter_weight(m, tri);
    if (HAS_QUADS && tri.meta.z != SHAPE_TRIANGLE) {
        Rect q = rect_of(tri);
        precise vec3 y = q.corner + u1 * q.ex + u2 * q.ey;
        // triangle_uv's weights are half a parallelogram's edge coordinates.
        return EmitterPoint(y, triangle_face_normal(p0, p1, p2), triangle_emission(m, tri, index, 0.5f * u1, 0.5f * u2),
                            weight);
    }
    // The square-root parameterization (Osada et al., "Shape Distributions",
    // 2002): barycentrics (1 - sqrt(u1), sqrt(u1) (1 - u2), sqrt(u1) u2) are
    // uniform by area.
    float su = sqrt(u1);
    precise vec3 y = (1.0f - su) * p0 + (su * (1.0f - u2)) * p1 + (su * u2) * p2;
    return EmitterPoint(y, triangle_face_normal(p0, p1, p2), triangle_emission(m, tri, index, su * (1.0f - u2), su * u2),
                        weight);
}

// A rectangle through its spherical rectangle, from in front of its emitting face and
// near it; anything else by area (density 0 behind).
bool triangle_light_sample(vec3 o, uint index, vec2 u, INOUT(LightSample) drawn) {
    if (!HAS_QUADS) {
        return false;
    }
    Triangle tri = load_triangle(index);
    if (tri.meta.z != SHAPE_RECTANGLE) {
        return false;
    }
    Rect q = rect_of(tri);
    vec3 normal = triangle_face_normal(vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
    SphericalRect sr;
    if (!(dot(o - q.corner, normal) > 0.0f && rect_by_solid_angle(o, q, sr))) {
        return false;
    }
    Material m = load_material(tri.meta.x);
    vec3 y = spherical_rect_point(sr, u.x, u.y);
    vec3 emission = m.emission;
    bool varies = (HAS_TEXTURES && m.emission_map != 0u) || (HAS_ALPHA && (tri.meta.y & TRIANGLE_ALPHA_TESTED) != 0u);
    if (varies) {
        // The point's coordinates along the edges, halved as triangle_uv takes them.
        vec3 d = y - q.corner;
        emission = triangle_emission(m, tri, index, 0.5f * dot(d, q.ex) / dot(q.ex, q.ex),
                                     0.5f * dot(d, q.ey) / dot(q.ey, q.ey));
    }
    float choice = triangle_emitter_weight(m, tri) * rect_area(q) / emitter_power();
    drawn = LightSample(y, normal, emission, choice / sr.solid_angle);
    return true;
}

bool triangle_light_pdf(vec3 o, uint index, float area_density, INOUT(float) pdf) {
    if (!HAS_QUADS) {
        return false;
    }
    Triangle tri = load_triangle(index);
    if (tri.meta.z != SHAPE_RECTANGLE) {
        return false;
    }
    Rect q = rect_of(tri);
    SphericalRect sr;
    if (!rect_by_solid_angle(o, q, sr)) {
        return false;
    }
    pdf = area_density * rect_area(q) / sr.solid_angle;
    return true;
}

#endif  // SHAPE_RECORDS
