// The surface model of global mode (global.glsl): a material is a sum of lobes,
//
//   diffuse  kd * diffuse / pi                                   Lambertian
//   glossy   ks * specular * (n + 2) / (2 pi) * cos(alpha)^n     normalized Phong
//   rough    GGX microfacet reflection (microfacet.glsl)          metallic-roughness
//   mirror   reflect                                             a delta lobe
//   glass    transmit, split by Fresnel (or all refracted with "fresnel": false),
//            delta lobes
//
// alpha lies between the incoming direction mirrored about the normal and the
// outgoing one; n is the shininess. The (n + 2) / (2 pi) factor (Lafortune & Willems,
// "Using the Modified Phong Reflectance Model for Physically Based Rendering", 1994)
// makes the glossy lobe reflect at most ks * specular of the light from the normal
// direction, so that a path's energy does not grow with the exponent, unlike the
// paper's unnormalized highlight of local mode.
//
// A metallic-roughness material (HAS_MICROFACET) has the diffuse and the rough lobes
// only. The rough lobe, of reflectance f0 at normal incidence, takes a share of the
// light that grows toward grazing angles by Fresnel's law; the diffuse lobe, of
// albedo (1 - metallic) base_color, gets what the rough lobe leaves, by the coupling
// of Shirley, Hu, Smits and Lafortune ("A Practitioners' Assessment of Light
// Reflection Models", 1997):
//
//   diffuse * (1 - f0) * 21 / (20 pi) * (1 - (1 - cos_i)^5) (1 - (1 - cos_o)^5)
//
// symmetric in wi and wo, and leaving from wo exactly the light a lobe of Schlick's
// reflectance f0 + (1 - f0)(1 - cos_o)^5 does not take; the rough lobe reflects no
// more than that, so the sum stays at most 1 (glTF's reference mix, (1 - F(wo.h))
// diffuse / pi, exceeds 1 near grazing angles).

// A scattering event picks one lobe group at random in proportion to its weight
// (the mean of its colour; for the rough lobe, of its Fresnel reflectance toward wo):
// the smooth group (diffuse + glossy + rough, sampled together as
// a mixture), the mirror or the glass. Dividing by the chosen group's probability
// keeps the estimate unbiased; next-event estimation and multiple importance
// sampling (global.glsl) apply to the smooth group only, as no light sample can
// land on a delta lobe.

struct Lobes {
    vec3 diffuse;     // kd * diffuse
    vec3 glossy;      // ks * specular (0 without HAS_SPECULAR)
    float shininess;
    vec3 f0;          // the rough lobe's reflectance at normal incidence
    float alpha;      // its GGX width; 0: no rough lobe (always without HAS_MICROFACET)
    vec3 mirror;      // reflect (0 without HAS_REFLECTION)
    vec3 glass;       // transmit (0 without HAS_REFRACTION)
    float ior;
    bool fresnel;
    float w_diffuse;  // the groups' selection weights: the means of their colours
    float w_glossy;
    float w_rough;
    float w_mirror;
    float w_glass;
};

float mean3(vec3 v) {
    return (v.x + v.y + v.z) * (1.0f / 3.0f);
}

// The lobes of material m seen from a direction at cos(theta_o) = cos_o to the
// shading normal, on which the rough lobe's selection weight depends.
Lobes material_lobes(Material m, float cos_o) {
    Lobes l;
    l.diffuse = vec3(m.diffuse_kd) * m.diffuse_kd.w;
    l.glossy = HAS_SPECULAR ? vec3(m.specular_ks) * m.specular_ks.w : vec3(0.0f);
    l.shininess = m.reflect_shininess.w;
    l.alpha = HAS_MICROFACET ? m.microfacet.w : 0.0f;
    l.f0 = l.alpha > 0.0f ? vec3(m.microfacet) : vec3(0.0f);
    l.mirror = HAS_REFLECTION ? vec3(m.reflect_shininess) : vec3(0.0f);
    l.glass = HAS_REFRACTION ? vec3(m.transmit_ior) : vec3(0.0f);
    l.ior = m.transmit_ior.w;
    l.fresnel = m.emission_fresnel.w != 0.0f;
    l.w_diffuse = mean3(l.diffuse);
    l.w_glossy = mean3(l.glossy);
    l.w_rough = 0.0f;
    if (l.alpha > 0.0f) {
        // The diffuse lobe's albedo seen from wo is its weight (the coupling's
        // constant makes the cos_i factor integrate to 1).
        bool above = cos_o > 0.0f;
        l.w_diffuse = above ? mean3(l.diffuse * (vec3(1.0f) - l.f0)) * (1.0f - schlick_scalar(cos_o)) : 0.0f;
        l.w_rough = above ? mean3(fresnel_schlick(l.f0, cos_o)) : 0.0f;
    }
    l.w_mirror = mean3(l.mirror);
    l.w_glass = mean3(l.glass);
    return l;
}

float lobes_total(Lobes l) {
    return l.w_diffuse + l.w_glossy + l.w_rough + l.w_mirror + l.w_glass;
}

// The smooth group's weight (diffuse + glossy + rough).
float smooth_weight(Lobes l) {
    return l.w_diffuse + l.w_glossy + l.w_rough;
}

// cos(alpha) for light arriving from wi and leaving toward wo: the cosine between wo
// and wi mirrored about n (symmetric in wi and wo).
float phong_cos_alpha(vec3 n, vec3 wo, vec3 wi) {
    return dot((2.0f * dot(n, wi)) * n - wi, wo);
}

// The smooth lobes' BSDF value for light from wi leaving toward wo (both unit,
// pointing away from the surface; n the shading normal on their side).
vec3 eval_smooth(Lobes l, vec3 n, vec3 wo, vec3 wi) {
    vec3 f = l.diffuse * (1.0f / PI);
    if (HAS_MICROFACET && l.alpha > 0.0f) {
        float coupling = (1.0f - schlick_scalar(dot(n, wi))) * (1.0f - schlick_scalar(dot(n, wo)));
        f *= (vec3(1.0f) - l.f0) * (21.0f / 20.0f * coupling);
        f += ggx_eval(l.f0, l.alpha, n, wo, wi);
    }
    if (HAS_SPECULAR && l.w_glossy > 0.0f) {
        float c = phong_cos_alpha(n, wo, wi);
        if (c > 0.0f) {
            f += l.glossy * ((l.shininess + 2.0f) / (2.0f * PI) * power(c, l.shininess));
        }
    }
    return f;
}

// The density over solid angle with which sample_smooth draws wi: the mixture of the
// hemisphere density (diffuse), the Phong lobe's (n + 1) / (2 pi) cos(alpha)^n
// around the mirror direction (glossy) and the visible normals' (rough), in
// proportion to their weights.
float pdf_smooth(Lobes l, Basis frame, vec3 wo, vec3 wi, uint hemisphere) {
    float w = smooth_weight(l);
    if (!(w > 0.0f)) {
        return 0.0f;
    }
    vec3 local = vec3(dot(wi, frame.t), dot(wi, frame.b), dot(wi, frame.n));
    float pdf = l.w_diffuse * hemisphere_pdf(hemisphere, local);
    if (HAS_SPECULAR && l.w_glossy > 0.0f) {
        float c = phong_cos_alpha(frame.n, wo, wi);
        if (c > 0.0f) {
            pdf += l.w_glossy * ((l.shininess + 1.0f) / (2.0f * PI) * power(c, l.shininess));
        }
    }
    if (HAS_MICROFACET && l.w_rough > 0.0f) {
        pdf += l.w_rough * ggx_pdf(l.alpha, frame.n, wo, wi);
    }
    return pdf / w;
}

// Draws wi from the smooth group: u0 picks diffuse, glossy or rough, (u1, u2) the
// direction.
// The glossy lobe is sampled exactly: cos(alpha) = u1^(1 / (n + 1)) around the mirror
// direction of wo. The result may point below the surface (the caller ends the path
// there: the lobes are zero on that side).
vec3 sample_smooth(Lobes l, Basis frame, vec3 wo, uint hemisphere, float u0, float u1, float u2) {
    float pick = u0 * smooth_weight(l);
    if (HAS_MICROFACET && l.w_rough > 0.0f && pick >= l.w_diffuse + l.w_glossy) {
        vec3 local = vec3(dot(wo, frame.t), dot(wo, frame.b), dot(wo, frame.n));
        return from_basis(frame, ggx_sample(l.alpha, local, u1, u2));
    }
    if (HAS_SPECULAR && l.w_glossy > 0.0f && pick >= l.w_diffuse) {
        vec3 mirrored = (2.0f * dot(frame.n, wo)) * frame.n - wo;
        float c = power(u1, 1.0f / (l.shininess + 1.0f));
        float s = sqrt(max(0.0f, 1.0f - c * c));
        return from_basis(basis_around(unit_vector(mirrored)), spherical_direction(c, s, 2.0f * PI * u2));
    }
    return from_basis(frame, sample_hemisphere(hemisphere, u1, u2));
}
