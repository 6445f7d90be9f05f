// The glossy lobe: normalized Phong, ks * specular * (n + 2) / (2 pi) * cos(alpha)^n,
// alpha between the incoming direction mirrored about the normal and the outgoing
// one, n the shininess. The (n + 2) / (2 pi) factor (Lafortune & Willems, "Using the
// Modified Phong Reflectance Model for Physically Based Rendering", 1994) makes it
// reflect at most ks * specular of the light from the normal direction, so that a
// path's energy does not grow with the exponent, unlike the paper's unnormalized
// highlight of local mode (phong.glsl).
//
// It is sampled exactly: cos(alpha) = u1^(1 / (n + 1)) around the mirror direction of
// wo, density (n + 1) / (2 pi) cos(alpha)^n. The sample may point below the surface
// (the caller ends the path there: the lobes are zero on that side).

struct GlossyLobe {
    vec3 color;       // ks * specular (0 without HAS_SPECULAR)
    float shininess;
    float weight;     // the mean of its colour
};

GlossyLobe glossy_lobe(Material m, float /* cos_o */) {
    GlossyLobe l;
    l.color = HAS_SPECULAR ? m.specular * m.ks : vec3(0.0f);
    l.shininess = m.shininess;
    l.weight = mean3(l.color);
    return l;
}

bool glossy_present(GlossyLobe l) {
    return HAS_SPECULAR && l.weight > 0.0f;
}

// cos(alpha) for light arriving from wi and leaving toward wo: the cosine between wo
// and wi mirrored about n (symmetric in wi and wo).
float phong_cos_alpha(vec3 n, vec3 wo, vec3 wi) {
    return dot((2.0f * dot(n, wi)) * n - wi, wo);
}

vec3 glossy_eval(GlossyLobe l, vec3 n, vec3 wo, vec3 wi) {
    float c = phong_cos_alpha(n, wo, wi);
    if (!(c > 0.0f)) {
        return vec3(0.0f);
    }
    return l.color * ((l.shininess + 2.0f) / (2.0f * PI) * power(c, l.shininess));
}

float glossy_pdf(GlossyLobe l, Basis frame, vec3 wo, vec3 wi, uint /* hemisphere */) {
    float c = phong_cos_alpha(frame.n, wo, wi);
    if (!(c > 0.0f)) {
        return 0.0f;
    }
    return (l.shininess + 1.0f) / (2.0f * PI) * power(c, l.shininess);
}

vec3 glossy_sample(GlossyLobe l, Basis frame, vec3 wo, uint /* hemisphere */, float u1, float u2) {
    vec3 mirrored = (2.0f * dot(frame.n, wo)) * frame.n - wo;
    float c = power(u1, 1.0f / (l.shininess + 1.0f));
    float s = sqrt(max(0.0f, 1.0f - c * c));
    return from_basis(basis_around(unit_vector(mirrored)), spherical_direction(c, s, 2.0f * PI * u2));
}
