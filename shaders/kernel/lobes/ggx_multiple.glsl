// The light the rough lobe (ggx.glsl) loses to scattering more than once between
// microfacets, given back as a lobe of its own (Kulla and Conty, "Revisiting
// Physically Based Shading at Imageworks", SIGGRAPH 2017 course):
//
//   f_ms(wo, wi) = F_ms (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg))
//
// E(mu) is the single-scattering lobe's albedo at cos(theta) = mu with a Fresnel of 1,
// and E_avg = 2 int_0^1 E(mu) mu dmu its mean over the cosine-weighted hemisphere, both
// for the material's alpha (ggx_albedo.glsl). Seen from wo, f_ms reflects
// F_ms (1 - E(mu_o)): with F = 1 exactly what the single-scattering lobe loses, so a
// white rough metal keeps all the light. F_ms is the Fresnel of the light that
// bounces on (ggx_multiple_fresnel).
//
// Drawn from the cosine-weighted hemisphere, whatever the render's hemisphere rule:
// f_ms is smooth and its cos(theta_i) factor dominates.

// Members in an order no other lobe record has (smooth_lobes.glsl says why).
struct GgxMultipleLobe {
    float alpha;
    float weight;   // its albedo seen from wo, mean over the colours
    vec3 scale;     // F_ms / (pi (1 - E_avg)): f_ms is this times (1 - E(mu_o)) (1 - E(mu_i))
};

GgxMultipleLobe ggx_multiple_lobe(Material m, float cos_o) {
    GgxMultipleLobe l;
    l.alpha = HAS_MICROFACET ? m.ggx_alpha : 0.0f;
    l.scale = vec3(0.0f);
    l.weight = 0.0f;
    if (l.alpha > 0.0f && cos_o > 0.0f) {
        float e_avg = ggx_mean_albedo(l.alpha);
        vec3 f_ms = ggx_multiple_fresnel(m.ggx_f0, material_f90(m), e_avg);
        // E_avg < 1 where E(mu) < 1 somewhere, which any alpha > 0 has; the guard keeps
        // a table rounded to 1 from dividing by zero.
        l.scale = e_avg < 1.0f ? f_ms * (1.0f / (PI * (1.0f - e_avg))) : vec3(0.0f);
        l.weight = e_avg < 1.0f ? mean3(f_ms) * (1.0f - ggx_albedo(cos_o, l.alpha)) : 0.0f;
    }
    return l;
}

bool ggx_multiple_present(GgxMultipleLobe l) {
    return HAS_MICROFACET && l.weight > 0.0f;
}

vec3 ggx_multiple_eval(GgxMultipleLobe l, vec3 n, vec3 wo, vec3 wi) {
    float co = dot(n, wo);
    float ci = dot(n, wi);
    if (!(co > 0.0f && ci > 0.0f)) {
        return vec3(0.0f);
    }
    return l.scale * ((1.0f - ggx_albedo(co, l.alpha)) * (1.0f - ggx_albedo(ci, l.alpha)));
}

float ggx_multiple_pdf(GgxMultipleLobe, Basis frame, vec3 /* wo */, vec3 wi, uint /* hemisphere */) {
    return max(dot(wi, frame.n), 0.0f) * (1.0f / PI);
}

vec3 ggx_multiple_sample(GgxMultipleLobe, Basis frame, vec3 /* wo */, uint /* hemisphere */, float u1, float u2) {
    return from_basis(frame, sample_hemisphere(HEMISPHERE_COSINE, u1, u2));
}
