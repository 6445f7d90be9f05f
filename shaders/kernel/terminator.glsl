// The shadow terminator: a coarse mesh shaded with interpolated normals looks round,
// but its shadow rays start on the flat facets, and near the terminator (where light
// grazes the surface) a facet's neighbours, rising above its plane, shadow points that
// the shading normal calls lit: dark speckles and a saw-toothed edge that follows the
// facets. Hanika ("Hacking the Shadow Terminator", Ray Tracing Gems II ch. 4, 2021)
// starts those rays on the smooth surface the vertex normals describe instead: p
// projected onto each vertex's tangent plane where it lies below it, the three
// projections blended with the barycentric weights, which is a quadratic patch
// through the vertices. Where the mesh is concave p lies above every tangent plane
// and stays where it is.
//
// Returns that move, for a hit at barycentrics (u, v) seen from the side the vertex
// normals face times `side` (+1 or -1), and zero unless it leaves the flat surface on
// the viewer's side (facing, the geometric normal toward the ray): broken normals
// must not move a ray's origin through the surface.
vec3 terminator_lift(Triangle tri, float u, float v, float side, vec3 facing) {
    float w = 1.0f - u - v;
    vec3 p0 = vec3(tri.p0), p1 = vec3(tri.p1), p2 = vec3(tri.p2);
    vec3 n0 = side * vec3(tri.n0), n1 = side * vec3(tri.n1), n2 = side * vec3(tri.n2);
    vec3 p = w * p0 + u * p1 + v * p2;
    // How far below each tangent plane p lies (0 where above it).
    float d0 = min(0.0f, dot(p - p0, n0));
    float d1 = min(0.0f, dot(p - p1, n1));
    float d2 = min(0.0f, dot(p - p2, n2));
    vec3 lift = -(w * d0 * n0 + u * d1 * n1 + v * d2 * n2);
    return dot(lift, facing) > 0.0f ? lift : vec3(0.0f);
}
