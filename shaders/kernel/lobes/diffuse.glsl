// The diffuse lobe: Lambertian, kd * diffuse / pi, drawn by the render's hemisphere
// rule (hemisphere.glsl).
//
// Under a rough lobe (a metallic-roughness material) it gets the light the rough lobe
// leaves, by the coupling of Shirley, Hu, Smits and Lafortune ("A Practitioners'
// Assessment of Light Reflection Models", 1997), for the rough lobe's reflectance f0
// at normal incidence:
//
//   diffuse * (1 - f0) * 21 / (20 pi) * (1 - (1 - cos_i)^5) (1 - (1 - cos_o)^5)
//
// symmetric in wi and wo, and leaving from wo exactly the light a lobe of Schlick's
// reflectance f0 + (1 - f0)(1 - cos_o)^5 does not take; the rough lobe reflects no
// more than that, so the sum stays at most 1 (glTF's reference mix, (1 - F(wo.h))
// diffuse / pi, exceeds 1 near grazing angles).

struct DiffuseLobe {
    vec3 albedo;    // kd * diffuse
    bool coupled;   // under the material's rough lobe
    vec3 f0;        // that lobe's reflectance at normal incidence (0 when not coupled)
    float weight;   // its albedo seen from wo: the selection weight
};

// The lobe of material m seen from cos(theta_o) = cos_o. Coupled, its albedo seen
// from wo is the weight (the coupling's constant makes the cos_i factor integrate
// to 1); from below it is 0.
DiffuseLobe diffuse_lobe(Material m, float cos_o) {
    DiffuseLobe l;
    l.albedo = m.diffuse * m.kd;
    l.coupled = HAS_MICROFACET && m.ggx_alpha > 0.0f;
    l.f0 = l.coupled ? m.ggx_f0 : vec3(0.0f);
    l.weight = mean3(l.albedo);
    if (l.coupled) {
        l.weight = cos_o > 0.0f ? mean3(l.albedo * (vec3(1.0f) - l.f0)) * (1.0f - schlick_scalar(cos_o)) : 0.0f;
    }
    return l;
}

// Evaluated whatever its weight: a coupled lobe seen from below still has a value.
bool diffuse_present(DiffuseLobe) {
    return true;
}

vec3 diffuse_eval(DiffuseLobe l, vec3 n, vec3 wo, vec3 wi) {
    vec3 f = l.albedo * (1.0f / PI);
    if (l.coupled) {
        float coupling = (1.0f - schlick_scalar(dot(n, wi))) * (1.0f - schlick_scalar(dot(n, wo)));
        f *= (vec3(1.0f) - l.f0) * (21.0f / 20.0f * coupling);
    }
    return f;
}

float diffuse_pdf(DiffuseLobe, Basis frame, vec3 /* wo */, vec3 wi, uint hemisphere) {
    vec3 local = vec3(dot(wi, frame.t), dot(wi, frame.b), dot(wi, frame.n));
    return hemisphere_pdf(hemisphere, local);
}

vec3 diffuse_sample(DiffuseLobe, Basis frame, vec3 /* wo */, uint hemisphere, float u1, float u2) {
    return from_basis(frame, sample_hemisphere(hemisphere, u1, u2));
}
