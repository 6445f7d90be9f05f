// Points on the area lights: the emissive primitives of the Emitter list
// (layout.glsl; built by host/flatten/flat_scene.cpp). An emitter is picked with
// probability proportional to its area, then a point uniformly on it, so the point
// is uniform over the total emitting area, of density 1 / total area whichever
// emitter it lies on: the estimator (area_lights.glsl) needs no per-emitter pdf.
//
// Every draw takes exactly three random numbers, in one fixed order, whatever it
// picks: both backends then consume identical streams, and the numbers a sample draws
// after a light sample do not depend on which emitter that sample chose.

struct EmitterPoint {
    vec3 position;
    vec3 normal;     // unit geometric normal on the emitting (front) side
    vec3 emission;   // radiance leaving the front face
};

// The first emitter whose cumulative area fraction exceeds u in [0, 1). The last
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
        if (u < load_emitter(mid).cdf_area.x) {
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
    return vec3(s * cos(phi), s * sin(phi), z);
}

// A point uniform by area on the emitter, from two uniform numbers.
EmitterPoint emitter_point(Emitter e, float u1, float u2) {
    uint kind = e.prim.x >> REF_KIND_SHIFT;
    uint index = e.prim.x & REF_INDEX_MASK;
    if (HAS_SPHERES && kind == REF_SPHERE) {
        Sphere s = load_sphere(index);
        vec3 n = uniform_sphere_direction(u1, u2);
        precise vec3 y = vec3(s.center_radius) + s.center_radius.w * n;
        return EmitterPoint(y, n, vec3(load_material(s.meta.x).emission_fresnel));
    }
    if (HAS_RINGS && kind == REF_RING) {
        // Uniform by area on the annulus: r^2 uniform between inner^2 and outer^2.
        Ring r = load_ring(index);
        vec3 n = vec3(r.normal_outer);
        Basis f = basis_around(n);
        float inner2 = r.center_inner.w * r.center_inner.w;
        float radius = sqrt(inner2 + u1 * (r.normal_outer.w * r.normal_outer.w - inner2));
        float phi = (2.0f * PI) * u2;
        precise vec3 y = vec3(r.center_inner) + (radius * cos(phi)) * f.t + (radius * sin(phi)) * f.b;
        return EmitterPoint(y, n, vec3(load_material(r.meta.x).emission_fresnel));
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
        vec3 radial = cos(phi) * f.t + sin(phi) * f.b;
        vec3 emission = vec3(load_material(c.meta.x).emission_fresnel);
        if (e.prim.y == CYLINDER_SIDE) {
            precise vec3 y = base + u1 * axis_vector + c.base_radius.w * radial;
            return EmitterPoint(y, radial, emission);
        }
        bool top = e.prim.y == CYLINDER_TOP_CAP;
        precise vec3 y = (top ? vec3(c.top_capped) : base) + (c.base_radius.w * sqrt(u1)) * radial;
        return EmitterPoint(y, top ? axis : -axis, emission);
    }
    if (HAS_TRIANGLES && kind == REF_TRIANGLE) {
        Triangle tri = load_triangle(index);
        // The square-root parameterization (Osada et al., "Shape Distributions",
        // 2002): barycentrics (1 - sqrt(u1), sqrt(u1) (1 - u2), sqrt(u1) u2) are
        // uniform by area.
        float su = sqrt(u1);
        vec3 p0 = vec3(tri.p0);
        vec3 p1 = vec3(tri.p1);
        vec3 p2 = vec3(tri.p2);
        precise vec3 y = (1.0f - su) * p0 + (su * (1.0f - u2)) * p1 + (su * u2) * p2;
        return EmitterPoint(y, triangle_face_normal(p0, p1, p2), vec3(load_material(tri.meta.x).emission_fresnel));
    }
    // Not reached for a list the host built; a zero normal faces nothing, so the
    // estimator skips the point.
    return EmitterPoint(vec3(0.0f), vec3(0.0f), vec3(0.0f));
}

// A point uniform over all emitting area: one number picks the emitter, two place
// the point, always drawn in this order.
EmitterPoint sample_emitters(INOUT(Rng) rng) {
    float u_pick = rng_next(rng);
    float u1 = rng_next(rng);
    float u2 = rng_next(rng);
    return emitter_point(load_emitter(pick_emitter(u_pick)), u1, u2);
}
