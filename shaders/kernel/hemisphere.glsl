// Directions on the hemisphere around a surface normal, for global illumination:
// an orthonormal basis around any unit normal, and three ways to draw a direction,
// each with its density over solid angle (what a Monte Carlo estimator divides by).

// Two unit tangents t, b with (t, b, n) orthonormal and right-handed, for any unit n.
// The branch-free construction of Duff et al., "Building an Orthonormal Basis,
// Revisited" (JCGT 2017): the sign of n.z picks the pole the formula stays away
// from, so 1 / (s + n.z) never divides by less than 1. n.z = -0 counts as +0, and
// both poles, the equator and +-0 components are all regular.
struct Basis {
    vec3 t;
    vec3 b;
    vec3 n;
};

Basis basis_around(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    return Basis(vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x), vec3(c, s + n.y * n.y * a, -n.y), n);
}

vec3 from_basis(Basis f, vec3 local) {
    return local.x * f.t + local.y * f.b + local.z * f.n;
}

// The direction at polar angle theta (from the normal) and azimuth phi, as
// (sin theta cos phi, sin theta sin phi, cos theta) in the basis.
vec3 spherical_direction(float cos_theta, float sin_theta, float phi) {
    vec2 sc = sin_cos(phi);
    return vec3(sin_theta * sc.y, sin_theta * sc.x, cos_theta);
}

// A direction in local coordinates (z along the normal) from two uniform numbers
// u1, u2 in [0, 1). theta never reaches pi/2 exactly, so cos(theta) > 0.
//   angles:  theta = u1 pi/2, phi = 2 pi u2. Uniform in (theta, phi), which is not
//            uniform on the hemisphere: the density over solid angle is
//            p(theta, phi) / sin(theta) = 1 / (pi^2 sin(theta)), crowding the pole.
//   uniform: cos(theta) = 1 - u1, density 1 / (2 pi).
//   cosine:  sin(theta) = sqrt(u1) (Malley's method: uniform on the disc, lifted),
//            density cos(theta) / pi.
vec3 sample_hemisphere(uint kind, float u1, float u2) {
    float phi = 2.0f * PI * u2;
    if (kind == HEMISPHERE_ANGLES) {
        float theta = 0.5f * PI * u1;
        vec2 sc = sin_cos(theta);
        return spherical_direction(sc.y, sc.x, phi);
    }
    if (kind == HEMISPHERE_UNIFORM) {
        float c = 1.0f - u1;
        return spherical_direction(c, sqrt(max(0.0f, 1.0f - c * c)), phi);
    }
    float s = sqrt(u1);
    return spherical_direction(sqrt(max(0.0f, 1.0f - u1)), s, phi);
}

// The density over solid angle of drawing local direction d with `kind`; 0 below
// the surface.
float hemisphere_pdf(uint kind, vec3 d) {
    if (!(d.z > 0.0f)) {
        return 0.0f;
    }
    if (kind == HEMISPHERE_ANGLES) {
        float sin_theta = sqrt(max(0.0f, 1.0f - d.z * d.z));
        return sin_theta > 0.0f ? 1.0f / (PI * PI * sin_theta) : INFINITY_T;
    }
    if (kind == HEMISPHERE_UNIFORM) {
        return 1.0f / (2.0f * PI);
    }
    return d.z / PI;
}
