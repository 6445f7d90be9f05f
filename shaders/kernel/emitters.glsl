// Points on the area lights: the emissive primitives of the Emitter list
// (layout.glsl; built by host/flatten/flat_scene.cpp). An emitter is picked with
// probability proportional to its power, area times mean emitted radiance, so a
// bright small lamp is not starved by a dim large one. Then a point on it: through
// the solid angle it covers where that can be drawn (solid_angle.glsl: a sphere's
// cone, a rectangle's spherical rectangle), else uniformly on its area. Picked so,
// a point of an emitter of mean radiance w has density w / emitter_power() over
// the emitting area, whichever emitter it lies on. A triangle with an emission
// texture is an emitter only where its own footprint in the texture emits, picked by
// its mean radiance over that footprint (triangle_emitter_weight), and sampled
// uniformly as any other; the estimate takes the textured radiance at the point
// drawn, over that density: unbiased, since the host counts a footprint black only
// where every texel the triangle's filtered look-ups can reach is black.
//
// Every draw takes exactly one slot (rng.glsl), whatever it picks: both backends then
// consume identical streams, and the numbers a sample draws after a light sample do
// not depend on which emitter that sample chose.

struct EmitterPoint {
    vec3 position;
    vec3 normal;     // unit geometric normal on the emitting (front) side
    vec3 emission;   // radiance leaving the front face, at this point
    float weight;    // the emitter's weight: its density is weight / emitter_power()
};

// The mean of an emission's channels: an emitter's power over pi times its area.
float emission_weight(vec3 emission) {
    return (emission.x + emission.y + emission.z) * (1.0f / 3.0f);
}

// The weight by which a triangle or quad of material m is picked, as the host
// weighs its power (flat_scene.cpp): its emission's, or with an emission texture
// the mean textured emission over its footprint, which the host stores in the record.
// Light samples' densities are built on it, never on the textured radiance at a
// point, so that sample_light and light_pdf_of_hit give one point one density.
float triangle_emitter_weight(Material m, Triangle tri) {
    return HAS_TEXTURES && m.emission_map != 0u ? uintBitsToFloat(tri.meta.w) : emission_weight(m.emission);
}

// The radiance a triangle or quad of material m emits at the point of weights
// (u, v) (triangle_uv): its emission, times its emission texture there.
vec3 triangle_emission(Material m, Triangle tri, float u, float v) {
    if (HAS_TEXTURES && m.emission_map != 0u) {
        return textured_emission(m, material_uv(m, triangle_uv(tri, u, v)));
    }
    return m.emission;
}

// The first emitter whose cumulative power fraction exceeds u in [0, 1). The last
// fraction is exactly 1, so there always is one.
uint pick_emitter(float u) {
    uint lo = 0u;
    uint hi = emitter_count() - 1u;
    loop_enter();
    while (lo < hi) {
        if (!loop_tick()) {
            break;  // the sample is flagged truncated; any index in range will do
        }
        uint mid = (lo + hi) / 2u;
        if (u < load_emitter(mid).cdf.x) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
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

// A point uniform by area on the emitter, from two uniform numbers.
EmitterPoint emitter_point(Emitter e, float u1, float u2) {
    uint kind = e.prim.x >> REF_KIND_SHIFT;
    uint index = e.prim.x & REF_INDEX_MASK;
    if (HAS_SPHERES && kind == REF_SPHERE) {
        Sphere s = load_sphere(index);
        vec3 n = uniform_sphere_direction(u1, u2);
        precise vec3 y = vec3(s.center_radius) + s.center_radius.w * n;
        vec3 emission = load_material(s.meta.x).emission;
        return EmitterPoint(y, n, emission, emission_weight(emission));
    }
    if (HAS_RINGS && kind == REF_RING) {
        // Uniform by area on the annulus: r^2 uniform between inner^2 and outer^2.
        Ring r = load_ring(index);
        vec3 n = vec3(r.normal_outer);
        Basis f = basis_around(n);
        float inner2 = r.center_inner.w * r.center_inner.w;
        float radius = sqrt(inner2 + u1 * (r.normal_outer.w * r.normal_outer.w - inner2));
        float phi = (2.0f * PI) * u2;
        vec2 sc = sin_cos(phi);
        precise vec3 y = vec3(r.center_inner) + (radius * sc.y) * f.t + (radius * sc.x) * f.b;
        vec3 emission = load_material(r.meta.x).emission;
        return EmitterPoint(y, n, emission, emission_weight(emission));
    }
    if (HAS_CYLINDERS && kind == REF_CYLINDER) {
        // The side uniform in height and angle; a cap as a disc (r^2 uniform). The
        // front faces are the outside: radially out, and out of each end.
        Cylinder c = load_cylinder(index);
        vec3 base = vec3(c.base_radius);
        vec3 axis_vector = vec3(c.top_capped) - base;
        vec3 axis = axis_vector / sqrt(dot(axis_vector, axis_vector));
        Basis f = basis_around(axis);
        float phi = (2.0f * PI) * u2;
        vec2 sc = sin_cos(phi);
        vec3 radial = sc.y * f.t + sc.x * f.b;
        vec3 emission = load_material(c.meta.x).emission;
        if (e.prim.y == CYLINDER_SIDE) {
            precise vec3 y = base + u1 * axis_vector + c.base_radius.w * radial;
            return EmitterPoint(y, radial, emission, emission_weight(emission));
        }
        bool top = e.prim.y == CYLINDER_TOP_CAP;
        precise vec3 y = (top ? vec3(c.top_capped) : base) + (c.base_radius.w * sqrt(u1)) * radial;
        return EmitterPoint(y, top ? axis : -axis, emission, emission_weight(emission));
    }
    if (HAS_TRIANGLES && kind == REF_TRIANGLE) {
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
            return EmitterPoint(y, triangle_face_normal(p0, p1, p2), triangle_emission(m, tri, 0.5f * u1, 0.5f * u2),
                                weight);
        }
        // The square-root parameterization (Osada et al., "Shape Distributions",
        // 2002): barycentrics (1 - sqrt(u1), sqrt(u1) (1 - u2), sqrt(u1) u2) are
        // uniform by area.
        float su = sqrt(u1);
        precise vec3 y = (1.0f - su) * p0 + (su * (1.0f - u2)) * p1 + (su * u2) * p2;
        return EmitterPoint(y, triangle_face_normal(p0, p1, p2), triangle_emission(m, tri, su * (1.0f - u2), su * u2),
                            weight);
    }
    // Not reached for a list the host built; a zero normal faces nothing, so the
    // estimator skips the point.
    return EmitterPoint(vec3(0.0f), vec3(0.0f), vec3(0.0f), 0.0f);
}

// A point on the lights as seen from a point o, and the density over solid angle at
// o of having drawn the direction toward it. pdf = 0: the sample carries no light
// (o lies behind a one-sided emitter), and no shadow ray need be traced.
struct LightSample {
    vec3 position;
    vec3 normal;     // unit geometric normal on the emitting (front) side
    vec3 emission;   // radiance leaving the front face
    float pdf;
};

float rect_area(Rect q) {
    return sqrt(dot(q.ex, q.ex) * dot(q.ey, q.ey));
}

float sphere_area(float radius) {
    return 4.0f * PI * radius * radius;
}

bool sampled_by_solid_angle(float solid_angle) {
    return solid_angle > MIN_SAMPLED_SOLID_ANGLE && solid_angle < MAX_SAMPLED_SOLID_ANGLE;
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
// rectangle: the one rule of sample_light and light_pdf_of_hit.
bool rect_by_solid_angle(vec3 o, Rect q, INOUT(SphericalRect) sr) {
    if (!near_rect(o, q)) {
        return false;
    }
    sr = spherical_rect(o, q.corner, q.ex, q.ey);
    return sampled_by_solid_angle(sr.solid_angle);
}

// The density over solid angle at o of a point y on an emitter drawn uniformly by
// area, with its density over area.
float area_to_solid_angle(float area_density, vec3 o, vec3 y, vec3 normal) {
    vec3 to_light = y - o;
    float r2 = dot(to_light, to_light);
    float cos_emitter = -dot(normal, to_light) / sqrt(r2);
    return cos_emitter > 0.0f ? min(area_density * r2 / cos_emitter, INFINITY_T) : 0.0f;
}

// One light sample for a point at o, from one slot: its first number picks the
// emitter and, rescaled to that emitter's share of [0, 1), places the point with the
// second. The samples of a pixel that pick one emitter are then those of the slot's
// Sobol points whose first number falls in that share, and such a subset of a net,
// rescaled, is a net again: each emitter's points stay stratified. (With the choice
// in a slot of its own, each emitter got a random subset of the points, spread no
// better than independent ones.) u is the slot's two numbers.
LightSample sample_light_from(vec3 o, vec2 u) {
    Emitter e = load_emitter(pick_emitter(u.x));
    // The largest float below 1 bounds it: rounding may bring the quotient up to 1.
    u.x = min((u.x - e.cdf.y) / (e.cdf.x - e.cdf.y), 0.99999994f);
    uint kind = e.prim.x >> REF_KIND_SHIFT;
    uint index = e.prim.x & REF_INDEX_MASK;
    if (HAS_SPHERES && kind == REF_SPHERE) {
        Sphere s = load_sphere(index);
        vec3 center = vec3(s.center_radius);
        SphereCone cone = sphere_cone(o, center, s.center_radius.w);
        float omega = sphere_cone_solid_angle(cone);
        if (sampled_by_solid_angle(omega)) {
            vec3 y = sphere_cone_point(o, cone, s.center_radius.w, u.x, u.y);
            vec3 emission = load_material(s.meta.x).emission;
            float choice = emission_weight(emission) * sphere_area(s.center_radius.w) / emitter_power();
            return LightSample(y, unit_vector(y - center), emission, choice / omega);
        }
    }
    if (HAS_TRIANGLES && kind == REF_TRIANGLE) {
        Triangle tri = load_triangle(index);
        if (HAS_QUADS && tri.meta.z == SHAPE_RECTANGLE) {
            Rect q = rect_of(tri);
            vec3 normal = triangle_face_normal(vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
            SphericalRect sr;
            // From behind the emitting face, or far, by area below (density 0 behind).
            if (dot(o - q.corner, normal) > 0.0f && rect_by_solid_angle(o, q, sr)) {
                Material m = load_material(tri.meta.x);
                vec3 y = spherical_rect_point(sr, u.x, u.y);
                vec3 emission = m.emission;
                if (HAS_TEXTURES && m.emission_map != 0u) {
                    // The point's coordinates along the edges, halved as triangle_uv takes them.
                    vec3 d = y - q.corner;
                    emission = triangle_emission(m, tri, 0.5f * dot(d, q.ex) / dot(q.ex, q.ex),
                                                 0.5f * dot(d, q.ey) / dot(q.ey, q.ey));
                }
                float choice = triangle_emitter_weight(m, tri) * rect_area(q) / emitter_power();
                return LightSample(y, normal, emission, choice / sr.solid_angle);
            }
        }
    }
    EmitterPoint y = emitter_point(e, u.x, u.y);
    float density = y.weight / emitter_power();
    return LightSample(y.position, y.normal, y.emission, area_to_solid_angle(density, o, y.position, y.normal));
}

LightSample sample_light(vec3 o, INOUT(Rng) rng) {
    return sample_light_from(o, rng_2d(rng));
}

// The density over solid angle with which sample_light, called at the ray's origin,
// draws the direction of a ray that hit an emitter's front face (for multiple
// importance sampling): the same choice of technique, from the same point, and the
// same density, from the emitter's weight rather than the radiance at the hit.
float light_pdf_of_hit(Ray ray, Hit hit) {
    uint kind = hit.prim >> REF_KIND_SHIFT;
    uint index = hit.prim & REF_INDEX_MASK;
    Material m = load_material(hit.material);
    float weight = emission_weight(m.emission);
    if (HAS_TEXTURES && HAS_TRIANGLES && kind == REF_TRIANGLE && m.emission_map != 0u) {
        weight = uintBitsToFloat(load_triangle(index).meta.w);
    }
    float area_density = weight / emitter_power();
    if (HAS_SPHERES && kind == REF_SPHERE) {
        Sphere s = load_sphere(index);
        float radius = s.center_radius.w;
        float omega = sphere_cone_solid_angle(sphere_cone(ray.origin, vec3(s.center_radius), radius));
        if (sampled_by_solid_angle(omega)) {
            return area_density * sphere_area(radius) / omega;
        }
    }
    if (HAS_TRIANGLES && kind == REF_TRIANGLE) {
        Triangle tri = load_triangle(index);
        if (HAS_QUADS && tri.meta.z == SHAPE_RECTANGLE) {
            Rect q = rect_of(tri);
            SphericalRect sr;
            if (rect_by_solid_angle(ray.origin, q, sr)) {
                return area_density * rect_area(q) / sr.solid_angle;
            }
        }
    }
    // geo_normal faces the ray, so this is the emitting face's cosine.
    float cos_emitter = -dot(hit.geo_normal, ray.dir);
    return min(area_density * hit.t * hit.t / cos_emitter, INFINITY_T);
}
