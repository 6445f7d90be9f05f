// Ray-primitive intersection: pure functions of their arguments (no buffers), so the
// unit tests call them directly through the reference backend.

// Nearest t in (t_min, t_max) where the ray meets the sphere, or INFINITY_T.
// Uses the form of the quadratic that does not cancel catastrophically (Haines et
// al., "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7):
// the discriminant comes from the distance between the centre and the ray's closest
// point rather than from b^2 - c, and the second root from c / q.
// `dir` must be unit length.
float intersect_sphere(Ray ray, vec3 center, float radius, float t_min, float t_max) {
    vec3 oc = ray.origin - center;
    float b = dot(oc, ray.dir);
    precise vec3 f = oc - b * ray.dir;
    float r2 = radius * radius;
    float disc = r2 - dot(f, f);
    if (!(disc >= 0.0f)) {
        return INFINITY_T;
    }
    float c = dot(oc, oc) - r2;
    float root = sqrt(disc);
    float q = b >= 0.0f ? -(b + root) : root - b;
    float t_a = q;
    float t_b = q != 0.0f ? c / q : 0.0f;
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

// Result of a ray-triangle test: t (INFINITY_T for a miss) and the barycentric
// weights u of p1 and v of p2 (p0 gets 1 - u - v).
struct TriangleHit {
    float t;
    float u;
    float v;
};

// Möller & Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection" (1997).
// Both faces are hit; a ray parallel to the plane (det exactly 0) misses.
TriangleHit intersect_triangle(Ray ray, vec3 p0, vec3 p1, vec3 p2, float t_min, float t_max) {
    TriangleHit miss = TriangleHit(INFINITY_T, 0.0f, 0.0f);
    vec3 e1 = p1 - p0;
    vec3 e2 = p2 - p0;
    vec3 pv = cross(ray.dir, e2);
    float det = dot(e1, pv);
    if (det == 0.0f) {
        return miss;
    }
    float inv_det = 1.0f / det;
    vec3 tv = ray.origin - p0;
    float u = dot(tv, pv) * inv_det;
    if (!(u >= 0.0f && u <= 1.0f)) {
        return miss;
    }
    vec3 qv = cross(tv, e1);
    float v = dot(ray.dir, qv) * inv_det;
    if (!(v >= 0.0f && u + v <= 1.0f)) {
        return miss;
    }
    float t = dot(e2, qv) * inv_det;
    if (!(t > t_min && t < t_max)) {
        return miss;
    }
    return TriangleHit(t, u, v);
}

// Unit geometric normal of a triangle, on its front side (cross(p1 - p0, p2 - p0)).
vec3 triangle_face_normal(vec3 p0, vec3 p1, vec3 p2) {
    return normalize(cross(p1 - p0, p2 - p0));
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
