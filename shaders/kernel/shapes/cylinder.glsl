// The cylinder (Cylinder, its record below): the side around the segment from base to top,
// and with `capped` the discs closing its ends; its outside is the front face. Its
// intersection, which reports the part hit, its test for the traversal, its hit
// record, and the points drawn on it when it emits, uniformly by area on one part
// (the host lists each part as an emitter of its own). The contract this file
// fulfils is in shapes/kinds.glsl.

#ifdef SHAPE_RECORDS  // the record, which layout.glsl includes

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
#define Cylinder_FROM_TEXELS(b, i) \
    Cylinder(fetch_vec4(b, 3u * (i)), fetch_vec4(b, 3u * (i) + 1u), fetch_texel(b, 3u * (i) + 2u))

#else  // the rest, which all.glsl includes

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

void test_cylinder(Ray ray, uint index, bool, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    Cylinder c = load_cylinder(index);
    CylinderHit ch = intersect_cylinder(ray, vec3(c.base_radius), vec3(c.top_capped), c.base_radius.w,
                                        c.top_capped.w != 0.0f, 0.0f, nearest.t);
    if (ch.t < nearest.t) {
        nearest.t = ch.t;
        nearest.ref = (REF_CYLINDER << REF_KIND_SHIFT) | index;
        nearest.part = ch.part;
    }
}

// No shading normal of its own: both normals are the geometric one, turned toward
// the ray. An open cylinder seen from within is its back face.
Hit cylinder_hit(Ray ray, uint index, Nearest nearest) {
    Cylinder c = load_cylinder(index);
    precise vec3 p = ray.origin + nearest.t * ray.dir;
    vec3 n = cylinder_normal(vec3(c.base_radius), vec3(c.top_capped), p, nearest.part);
    bool front = dot(n, ray.dir) < 0.0f;
    vec3 facing = front ? n : -n;
    return Hit(nearest.t, facing, facing, vec3(0.0f), c.meta.x, front, (REF_CYLINDER << REF_KIND_SHIFT) | index,
               vec2(0.0f), vec2(0.0f));
}

float cylinder_pick_weight(uint, Material m) {
    return emission_weight(m.emission);
}

// The side uniform in height and angle; a cap as a disc (r^2 uniform). The front
// faces are the outside: radially out, and out of each end.
EmitterPoint cylinder_emitter_point(uint index, uint part, float u1, float u2) {
    Cylinder c = load_cylinder(index);
    vec3 base = vec3(c.base_radius);
    vec3 axis_vector = vec3(c.top_capped) - base;
    vec3 axis = axis_vector / sqrt(dot(axis_vector, axis_vector));
    Basis f = basis_around(axis);
    float phi = (2.0f * PI) * u2;
    vec2 sc = sin_cos(phi);
    vec3 radial = sc.y * f.t + sc.x * f.b;
    vec3 emission = load_material(c.meta.x).emission;
    if (part == CYLINDER_SIDE) {
        precise vec3 y = base + u1 * axis_vector + c.base_radius.w * radial;
        return EmitterPoint(y, radial, emission, emission_weight(emission));
    }
    bool top = part == CYLINDER_TOP_CAP;
    precise vec3 y = (top ? vec3(c.top_capped) : base) + (c.base_radius.w * sqrt(u1)) * radial;
    return EmitterPoint(y, top ? axis : -axis, emission, emission_weight(emission));
}

// Always by area.
bool cylinder_light_sample(vec3, uint, vec2, INOUT(LightSample)) {
    return false;
}

bool cylinder_light_pdf(vec3, uint, float, INOUT(float)) {
    return false;
}

#endif  // SHAPE_RECORDS
