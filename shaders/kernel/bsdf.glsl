// The surface model of global mode (global.glsl): a material is a sum of lobes,
//
//   diffuse  kd * diffuse / pi                                   Lambertian
//   glossy   ks * specular * (n + 2) / (2 pi) * cos(alpha)^n     normalized Phong
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
// A scattering event picks one lobe group at random in proportion to its weight
// (the mean of its colour): the smooth group (diffuse + glossy, sampled together as
// a mixture), the mirror or the glass. Dividing by the chosen group's probability
// keeps the estimate unbiased; next-event estimation and multiple importance
// sampling (global.glsl) apply to the smooth group only, as no light sample can
// land on a delta lobe.

struct Lobes {
    vec3 diffuse;     // kd * diffuse
    vec3 glossy;      // ks * specular (0 without HAS_SPECULAR)
    float shininess;
    vec3 mirror;      // reflect (0 without HAS_REFLECTION)
    vec3 glass;       // transmit (0 without HAS_REFRACTION)
    float ior;
    bool fresnel;
    float w_diffuse;  // the groups' selection weights: the means of their colours
    float w_glossy;
    float w_mirror;
    float w_glass;
};

float mean3(vec3 v) {
    return (v.x + v.y + v.z) * (1.0f / 3.0f);
}

Lobes material_lobes(Material m) {
    Lobes l;
    l.diffuse = vec3(m.diffuse_kd) * m.diffuse_kd.w;
    l.glossy = HAS_SPECULAR ? vec3(m.specular_ks) * m.specular_ks.w : vec3(0.0f);
    l.shininess = m.reflect_shininess.w;
    l.mirror = HAS_REFLECTION ? vec3(m.reflect_shininess) : vec3(0.0f);
    l.glass = HAS_REFRACTION ? vec3(m.transmit_ior) : vec3(0.0f);
    l.ior = m.transmit_ior.w;
    l.fresnel = m.emission_fresnel.w != 0.0f;
    l.w_diffuse = mean3(l.diffuse);
    l.w_glossy = mean3(l.glossy);
    l.w_mirror = mean3(l.mirror);
    l.w_glass = mean3(l.glass);
    return l;
}

float lobes_total(Lobes l) {
    return l.w_diffuse + l.w_glossy + l.w_mirror + l.w_glass;
}

// The probability of picking the smooth group (diffuse + glossy).
float smooth_probability(Lobes l) {
    float total = lobes_total(l);
    return total > 0.0f ? (l.w_diffuse + l.w_glossy) / total : 0.0f;
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
    if (HAS_SPECULAR && l.w_glossy > 0.0f) {
        float c = phong_cos_alpha(n, wo, wi);
        if (c > 0.0f) {
            f += l.glossy * ((l.shininess + 2.0f) / (2.0f * PI) * power(c, l.shininess));
        }
    }
    return f;
}

// The density over solid angle with which sample_smooth draws wi: the mixture of the
// hemisphere density (diffuse) and the Phong lobe's (n + 1) / (2 pi) cos(alpha)^n
// around the mirror direction (glossy), in proportion to their weights.
float pdf_smooth(Lobes l, Basis frame, vec3 wo, vec3 wi, uint hemisphere) {
    float w = l.w_diffuse + l.w_glossy;
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
    return pdf / w;
}

// Draws wi from the smooth group: u0 picks diffuse or glossy, (u1, u2) the direction.
// The glossy lobe is sampled exactly: cos(alpha) = u1^(1 / (n + 1)) around the mirror
// direction of wo. The result may point below the surface (the caller ends the path
// there: the lobes are zero on that side).
vec3 sample_smooth(Lobes l, Basis frame, vec3 wo, uint hemisphere, float u0, float u1, float u2) {
    float w = l.w_diffuse + l.w_glossy;
    if (HAS_SPECULAR && l.w_glossy > 0.0f && u0 * w >= l.w_diffuse) {
        vec3 mirrored = (2.0f * dot(frame.n, wo)) * frame.n - wo;
        float c = power(u1, 1.0f / (l.shininess + 1.0f));
        float s = sqrt(max(0.0f, 1.0f - c * c));
        return from_basis(basis_around(unit_vector(mirrored)), spherical_direction(c, s, 2.0f * PI * u2));
    }
    return from_basis(frame, sample_hemisphere(hemisphere, u1, u2));
}
