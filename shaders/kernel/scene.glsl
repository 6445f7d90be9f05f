// Visibility queries over the scene's primitive buffers. Brute force over every
// primitive for now; each primitive test is one budgeted loop iteration.

const uint PRIM_NONE = 0u;
const uint PRIM_SPHERE = 1u;
const uint PRIM_TRIANGLE = 2u;

Hit sphere_hit(Ray ray, uint index, float t) {
    Sphere s = load_sphere(index);
    vec3 center = vec3(s.center_radius);
    precise vec3 p = ray.origin + t * ray.dir;
    vec3 n = (p - center) / s.center_radius.w;
    bool front = dot(n, ray.dir) < 0.0f;
    vec3 facing = front ? n : -n;
    return Hit(t, facing, facing, s.meta.x, front);
}

Hit triangle_hit(Ray ray, uint index, TriangleHit th) {
    Triangle tri = load_triangle(index);
    vec3 ng = triangle_face_normal(vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
    vec3 ns = ng;
    if (HAS_SMOOTH_NORMALS && tri.meta.y != 0u) {
        ns = interpolate_normal(vec3(tri.n0), vec3(tri.n1), vec3(tri.n2), th.u, th.v, ng);
    }
    bool front = dot(ng, ray.dir) < 0.0f;
    vec3 g = front ? ng : -ng;
    // The shading normal must lie on the viewer's side of the surface too.
    vec3 s = dot(ns, g) < 0.0f ? -ns : ns;
    return Hit(th.t, s, g, tri.meta.x, front);
}

// The closest hit with t in (0, t_max).
Hit closest_hit(Ray ray, float t_max) {
    float closest = t_max;
    uint kind = PRIM_NONE;
    uint index = 0u;
    TriangleHit best_tri = TriangleHit(INFINITY_T, 0.0f, 0.0f);
    if (HAS_SPHERES) {
        loop_enter();
        for (uint i = 0u; i < params.counts.x; ++i) {
            if (!loop_tick()) {
                break;
            }
            Sphere s = load_sphere(i);
            float t = intersect_sphere(ray, vec3(s.center_radius), s.center_radius.w, 0.0f, closest);
            if (t < closest) {
                closest = t;
                kind = PRIM_SPHERE;
                index = i;
            }
        }
    }
    if (HAS_TRIANGLES) {
        loop_enter();
        for (uint i = 0u; i < params.counts.y; ++i) {
            if (!loop_tick()) {
                break;
            }
            Triangle tri = load_triangle(i);
            TriangleHit th = intersect_triangle(ray, vec3(tri.p0), vec3(tri.p1), vec3(tri.p2), 0.0f, closest);
            if (th.t < closest) {
                closest = th.t;
                kind = PRIM_TRIANGLE;
                index = i;
                best_tri = th;
            }
        }
    }
    if (kind == PRIM_SPHERE) {
        return sphere_hit(ray, index, closest);
    }
    if (kind == PRIM_TRIANGLE) {
        return triangle_hit(ray, index, best_tri);
    }
    return no_hit();
}

// True when anything lies on the ray with t in (0, t_max): shadow rays stop at the
// first blocker, whichever it is.
bool occluded(Ray ray, float t_max) {
    if (HAS_SPHERES) {
        loop_enter();
        for (uint i = 0u; i < params.counts.x; ++i) {
            if (!loop_tick()) {
                return false;
            }
            Sphere s = load_sphere(i);
            if (intersect_sphere(ray, vec3(s.center_radius), s.center_radius.w, 0.0f, t_max) < t_max) {
                return true;
            }
        }
    }
    if (HAS_TRIANGLES) {
        loop_enter();
        for (uint i = 0u; i < params.counts.y; ++i) {
            if (!loop_tick()) {
                return false;
            }
            Triangle tri = load_triangle(i);
            if (intersect_triangle(ray, vec3(tri.p0), vec3(tri.p1), vec3(tri.p2), 0.0f, t_max).t < t_max) {
                return true;
            }
        }
    }
    return false;
}
