// The ring (Ring, its record below): an annulus around a centre, in the plane across its
// normal, the front face on the normal's side. Its intersection, its test for the
// traversal, its hit record, and the points drawn on it when it emits, uniformly by
// area. The contract this file fulfils is in shapes/kinds.glsl.

#ifdef SHAPE_RECORDS  // the record, which layout.glsl includes

// A ring (annulus) in the plane through `center` perpendicular to `normal`: the points
// whose distance from the centre lies in [inner, outer] (inner 0: a disc). The normal
// is unit length (the loader normalizes it) and marks the front face. meta.x =
// material index.
struct Ring {
    vec4 center_inner;  // xyz centre, w inner radius
    vec4 normal_outer;  // xyz unit normal (front side), w outer radius
    uvec4 meta;
};
#define Ring_FROM_TEXELS(b, i) Ring(fetch_vec4(b, 3u * (i)), fetch_vec4(b, 3u * (i) + 1u), fetch_texel(b, 3u * (i) + 2u))

#else  // the rest, which all.glsl includes

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

void test_ring(Ray ray, uint index, bool, INOUT(Nearest) nearest) {
    g_intersection_tests += 1u;
    Ring r = load_ring(index);
    float t = intersect_ring(ray, vec3(r.center_inner), vec3(r.normal_outer), r.center_inner.w,
                             r.normal_outer.w, 0.0f, nearest.t);
    if (t < nearest.t) {
        nearest.t = t;
        nearest.ref = (REF_RING << REF_KIND_SHIFT) | index;
    }
}

// No shading normal of its own: both normals are the geometric one, turned toward
// the ray.
Hit ring_hit(Ray ray, uint index, Nearest nearest) {
    Ring r = load_ring(index);
    vec3 n = vec3(r.normal_outer);
    bool front = dot(n, ray.dir) < 0.0f;
    vec3 facing = front ? n : -n;
    return Hit(nearest.t, facing, facing, vec3(0.0f), r.meta.x, front, (REF_RING << REF_KIND_SHIFT) | index,
               vec2(0.0f), vec2(0.0f));
}

float ring_pick_weight(uint, Material m) {
    return emission_weight(m.emission);
}

// Uniform by area on the annulus: r^2 uniform between inner^2 and outer^2.
EmitterPoint ring_emitter_point(uint index, uint, float u1, float u2) {
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

// Always by area.
bool ring_light_sample(vec3, uint, vec2, INOUT(LightSample)) {
    return false;
}

bool ring_light_pdf(vec3, uint, float, INOUT(float)) {
    return false;
}

#endif  // SHAPE_RECORDS
