// Mirror reflection and refraction at a surface: directions and the Fresnel
// reflectance. `n` is the unit shading normal on the side the ray arrives from
// (Hit.normal), `d` the unit direction of the arriving ray.

// Renormalized: d and n are unit only to rounding, and the error would compound over
// a chain of mirrors.
vec3 mirror_direction(vec3 d, vec3 n) {
    precise vec3 r = d - (2.0f * dot(d, n)) * n;
    return unit_vector(r);
}

struct Refraction {
    vec3 dir;           // the refracted direction, unit length; zero when total
    float reflectance;  // the Fresnel reflectance R: the transmitted share is 1 - R
    bool total;         // total internal reflection: no refracted ray, R = 1
};

// Snell's law and the exact Fresnel equations for unpolarized light (the mean of the
// s- and p-polarized reflectances) at an interface with relative index eta =
// n_incident / n_transmitted. Exact rather than Schlick's approximation: it costs a
// handful of flops on a hit that already pays for a ray, and Schlick's error grows
// away from ior 1.5 and, on the denser side, needs the transmitted angle anyway.
// At and beyond the critical angle all energy is reflected.
Refraction refract_fresnel(vec3 d, vec3 n, float eta) {
    precise float cos_i = clamp(-dot(d, n), 0.0f, 1.0f);
    precise float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
    if (!(sin2_t < 1.0f)) {
        return Refraction(vec3(0.0f), 1.0f, true);
    }
    precise float cos_t = sqrt(1.0f - sin2_t);
    // Dividing the textbook forms by n_transmitted leaves only eta.
    precise float r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    precise float r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    precise vec3 t = eta * d + (eta * cos_i - cos_t) * n;
    precise float reflectance = 0.5f * (r_s * r_s + r_p * r_p);
    return Refraction(unit_vector(t), reflectance, false);
}
