// Directions toward a shape drawn uniformly over the solid angle it covers, seen from
// a point: a light sampled so has a constant density, 1 / solid angle, where drawing
// a point uniformly on its area would weigh each direction by distance^2 / cosine
// and add that spread to the noise of every light sample (emitters.glsl).

// Outside this range the float arithmetic of the solid angle loses too many digits
// (a shape far away or seen edge-on covers almost nothing; a point on a rectangle's
// plane inside it sees almost a hemisphere), and the light is sampled by area instead.
const float MIN_SAMPLED_SOLID_ANGLE = 1.0e-3f;
const float MAX_SAMPLED_SOLID_ANGLE = 6.2f;

bool sampled_by_solid_angle(float solid_angle) {
    return solid_angle > MIN_SAMPLED_SOLID_ANGLE && solid_angle < MAX_SAMPLED_SOLID_ANGLE;
}

// Rectangles are sampled by solid angle from points within this many of their
// diagonals of their centre (shapes/triangle.glsl, near_rect).
const float RECT_NEAR = 2.0f;

// A rectangle (corner, perpendicular edges ex and ey) seen from o, set up as in
// Ureña, Fajardo & King, "An Area-Preserving Parametrization for Spherical
// Rectangles" (EGSR 2013), section 3: a frame x, y along the edges and z away from
// the rectangle's side of o, the rectangle's extent [x0, x1] x [y0, y1] at height z0
// < 0 in it, and the spherical rectangle's solid angle.
//
// Two departures from the paper keep the digits that both backends agree on. The
// solid angle is not the sum of the four corner angles less 2 pi, which cancels to a
// small difference of large terms, but the two halves' solid angles by Van Oosterom
// and Strackee's formula, whose terms have no cancellation in this frame. And k, the
// paper's 2 pi - gamma2 - gamma3, is kept as its cosine and sine, computed from the
// corner angles' cosines without acos: then no inverse trigonometric function is
// evaluated, whose implementations differ most between devices.
struct SphericalRect {
    vec3 o;
    vec3 x;
    vec3 y;
    vec3 z;
    float x0;
    float x1;
    float y0;
    float y1;
    float z0;
    float b0;           // z of the normals of the planes through o and the edges y = y0 and y = y1
    float b1;
    float cos_k;        // k = 2 pi minus the two angles at the edge x = x0
    float sin_k;
    float solid_angle;
};

// The solid angle of the triangle (a, b, c) seen from the origin, whose triple
// product a . (b x c) is `triple` (Van Oosterom & Strackee 1983); la, lb, lc are the
// lengths.
float triangle_solid_angle(vec3 a, vec3 b, vec3 c, float la, float lb, float lc, float triple) {
    float den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    return 2.0f * upper_half_plane_angle(triple, den);
}

SphericalRect spherical_rect(vec3 o, vec3 corner, vec3 ex, vec3 ey) {
    SphericalRect r;
    float ex_len = sqrt(dot(ex, ex));
    float ey_len = sqrt(dot(ey, ey));
    r.o = o;
    r.x = ex / ex_len;
    r.y = ey / ey_len;
    r.z = cross(r.x, r.y);
    vec3 d = corner - o;
    r.x0 = dot(d, r.x);
    r.y0 = dot(d, r.y);
    r.z0 = dot(d, r.z);
    if (r.z0 > 0.0f) {
        r.z0 = -r.z0;
        r.z = -r.z;
    }
    r.x1 = r.x0 + ex_len;
    r.y1 = r.y0 + ey_len;
    // The unit normals of the planes through o and each edge, written out: n0 (edge
    // y = y0) = (0, z0, -y0) / l0, n1 (x = x1) = (-z0, 0, x1) / l1, n2 (y = y1) =
    // (0, -z0, y1) / l2, n3 (x = x0) = (z0, 0, -x0) / l3.
    float z2 = r.z0 * r.z0;
    float l0 = sqrt(z2 + r.y0 * r.y0);
    float l2 = sqrt(z2 + r.y1 * r.y1);
    float l3 = sqrt(z2 + r.x0 * r.x0);
    // The corner angles at x = x0: cos(gamma) = -n_i . n_j, sin(gamma) >= 0.
    float c2 = clamp(r.y1 * r.x0 / (l2 * l3), -1.0f, 1.0f);
    float c3 = clamp(-r.x0 * r.y0 / (l3 * l0), -1.0f, 1.0f);
    float s2 = sqrt(1.0f - c2 * c2);
    float s3 = sqrt(1.0f - c3 * c3);
    r.cos_k = c2 * c3 - s2 * s3;       // cos(2 pi - g2 - g3) = cos(g2 + g3)
    r.sin_k = -(s2 * c3 + c2 * s3);    // sin(2 pi - g2 - g3) = -sin(g2 + g3)
    r.b0 = -r.y0 / l0;
    r.b1 = r.y1 / l2;
    // The corners, and the halves (v00, v10, v11) and (v00, v11, v01), whose triple
    // products are both |z0| ex_len ey_len.
    vec3 v00 = vec3(r.x0, r.y0, r.z0);
    vec3 v10 = vec3(r.x1, r.y0, r.z0);
    vec3 v11 = vec3(r.x1, r.y1, r.z0);
    vec3 v01 = vec3(r.x0, r.y1, r.z0);
    float d00 = sqrt(dot(v00, v00));
    float d10 = sqrt(dot(v10, v10));
    float d11 = sqrt(dot(v11, v11));
    float d01 = sqrt(dot(v01, v01));
    float triple = -r.z0 * ex_len * ey_len;
    r.solid_angle = triangle_solid_angle(v00, v10, v11, d00, d10, d11, triple) +
                    triangle_solid_angle(v00, v11, v01, d00, d11, d01, triple);
    return r;
}

// The point of the rectangle in the direction of solid-angle fractions (u, v): the
// sub-rectangle [x0, xu] x [y0, y1] covers u of the solid angle, and along x = xu the
// height yv splits the remaining arc's projection in the ratio v (the paper's
// Algorithm 1, with sin and cos of k + u S by the angle-sum rule).
vec3 spherical_rect_point(SphericalRect r, float u, float v) {
    float a = u * r.solid_angle;
    vec2 sc = sin_cos(a);
    float sin_a = sc.x;
    float cos_a = sc.y;
    float cos_au = cos_a * r.cos_k - sin_a * r.sin_k;
    float sin_au = sin_a * r.cos_k + cos_a * r.sin_k;
    float cu = 0.0f;  // the limit where sin(au) vanishes: xu = 0
    if (sin_au != 0.0f) {
        float fu = (cos_au * r.b0 - r.b1) / sin_au;
        cu = clamp((fu > 0.0f ? 1.0f : -1.0f) / sqrt(fu * fu + r.b0 * r.b0), -1.0f, 1.0f);
    }
    float xu = clamp(-(cu * r.z0) / sqrt(max(1.0f - cu * cu, 1.0e-12f)), r.x0, r.x1);
    float d = sqrt(xu * xu + r.z0 * r.z0);
    float h0 = r.y0 / sqrt(d * d + r.y0 * r.y0);
    float h1 = r.y1 / sqrt(d * d + r.y1 * r.y1);
    float hv = h0 + v * (h1 - h0);
    float hv2 = hv * hv;
    float yv = hv2 < 1.0f - 1.0e-6f ? clamp(hv * d / sqrt(1.0f - hv2), r.y0, r.y1) : r.y1;
    precise vec3 p = r.o + xu * r.x + yv * r.y + r.z0 * r.z;
    return p;
}

// The cone of directions from o that meet a sphere (centre c, radius) outside it:
// half-angle theta_max with sin^2 = radius^2 / distance^2. 1 - cos(theta_max) is
// written as sin^2 / (1 + cos), which keeps its digits for a small, far sphere.
struct SphereCone {
    vec3 axis;           // unit, from o to the centre
    float distance;
    float one_minus_cos; // 1 - cos(theta_max); 0 when o is not outside the sphere
};

SphereCone sphere_cone(vec3 o, vec3 center, float radius) {
    vec3 d = center - o;
    float dist2 = dot(d, d);
    float sin2 = radius * radius / dist2;
    SphereCone c;
    c.distance = sqrt(dist2);
    c.axis = d / c.distance;
    c.one_minus_cos = sin2 < 1.0f ? sin2 / (1.0f + sqrt(1.0f - sin2)) : 0.0f;
    return c;
}

float sphere_cone_solid_angle(SphereCone c) {
    return 2.0f * PI * c.one_minus_cos;
}

// The point where the direction at fractions (u1, u2) of the cone meets the sphere
// first: cos(theta) uniform between cos(theta_max) and 1, the angle around the axis
// uniform. 1 - cos(theta) = u1 (1 - cos(theta_max)) is used as it is, so sin(theta)
// keeps its digits near the axis too.
vec3 sphere_cone_point(vec3 o, SphereCone c, float radius, float u1, float u2) {
    float one_minus_cos = u1 * c.one_minus_cos;
    float cos_theta = 1.0f - one_minus_cos;
    float sin2 = max(0.0f, one_minus_cos * (2.0f - one_minus_cos));
    vec3 dir = from_basis(basis_around(c.axis), spherical_direction(cos_theta, sqrt(sin2), 2.0f * PI * u2));
    // Along dir the sphere is entered at t = D cos(theta) - sqrt(r^2 - D^2 sin^2(theta)).
    float t = c.distance * cos_theta - sqrt(max(0.0f, radius * radius - c.distance * c.distance * sin2));
    precise vec3 p = o + t * dir;
    return p;
}
