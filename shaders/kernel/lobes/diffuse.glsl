// The diffuse lobe: Lambertian, kd * diffuse / pi, drawn by the render's hemisphere
// rule (hemisphere.glsl).
//
// Under a rough lobe (a metallic-roughness material) it gets the light the rough lobe
// leaves, as Kulla and Conty ("Revisiting Physically Based Shading at Imageworks",
// 2017) layer a diffuse base under a specular coat. With R(mu) what the rough lobe
// reflects from cos(theta) = mu, single and multiple scattering together, and R_avg
// its mean over the cosine-weighted hemisphere (ggx_albedo.glsl):
//
//   diffuse (1 - R(mu_o)) (1 - R(mu_i)) / (pi (1 - R_avg))
//
// symmetric in wi and wo, and reflecting from wo diffuse (1 - R(mu_o)): a white base
// under any rough coat reflects all the light, and no base more.

struct DiffuseLobe {
    vec3 albedo;    // kd * diffuse
    bool coupled;   // under the material's rough lobe
    vec3 f0;        // that lobe's reflectance at normal incidence (0 when not coupled)
    float f90;      // and at grazing incidence (fresnel.glsl)
    float alpha;    // its width (0 when not coupled)
    vec3 scale;     // the value but for the (1 - R) factors: albedo / (pi (1 - R_avg)), or albedo / pi
    float weight;   // its albedo seen from wo: the selection weight
};

// The lobe of material m seen from cos(theta_o) = cos_o; from below a coupled one
// weighs 0.
DiffuseLobe diffuse_lobe(Material m, float cos_o) {
    DiffuseLobe l;
    l.albedo = m.diffuse * m.kd;
    l.coupled = HAS_MICROFACET && m.ggx_alpha > 0.0f;
    l.f0 = l.coupled ? m.ggx_f0 : vec3(0.0f);
    l.f90 = material_f90(m);
    l.alpha = l.coupled ? m.ggx_alpha : 0.0f;
    l.scale = l.albedo * (1.0f / PI);
    l.weight = mean3(l.albedo);
    if (l.coupled) {
        // R_avg < 1 unless f0 = 1, which only a metal without a diffuse lobe has.
        vec3 left = vec3(1.0f) - ggx_mean_reflectance(l.f0, l.f90, l.alpha);
        l.scale = vec3(left.x > 0.0f ? l.scale.x / left.x : 0.0f, left.y > 0.0f ? l.scale.y / left.y : 0.0f,
                       left.z > 0.0f ? l.scale.z / left.z : 0.0f);
        l.weight = cos_o > 0.0f ? mean3(l.albedo * (vec3(1.0f) - ggx_reflectance(l.f0, l.f90, cos_o, l.alpha))) : 0.0f;
    }
    return l;
}

// Evaluated whatever its weight (an uncoupled lobe has a value from below too).
bool diffuse_present(DiffuseLobe) {
    return true;
}

vec3 diffuse_eval(DiffuseLobe l, vec3 n, vec3 wo, vec3 wi) {
    vec3 f = l.scale;
    if (l.coupled) {
        float co = dot(n, wo);
        float ci = dot(n, wi);
        if (!(co > 0.0f && ci > 0.0f)) {
            return vec3(0.0f);
        }
        f *= (vec3(1.0f) - ggx_reflectance(l.f0, l.f90, co, l.alpha)) *
             (vec3(1.0f) - ggx_reflectance(l.f0, l.f90, ci, l.alpha));
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
