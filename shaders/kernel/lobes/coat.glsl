// The clear coat of a metallic-roughness material (glTF's KHR_materials_clearcoat): a
// colourless dielectric layer of index 1.5 (reflecting 0.04 at normal incidence) over
// the rest of the material, a GGX lobe of its own width (ggx.glsl) weighted by the
// coat factor c. What the coat reflects does not reach the layers under it: they are
// weighed by what it lets through toward the viewer,
//
//   f = c f_coat + (1 - c R_coat(mu_o)) f_base,
//
// with R_coat(mu) = f0 E(mu) + (1 - f0) E_s(mu) the coat's single-scattering albedo
// from the tables (ggx_albedo.glsl), so that a base that reflects all the light keeps
// reflecting all of it under any coat (the coat's own multiple scattering, at f0 =
// 0.04 under 0.2% of the light, is not followed; tests/kernel/microfacet_test.cpp). Weighing by mu_o alone (albedo scaling)
// keeps the sum's energy but not its reciprocity; bsdf.glsl applies the factor to the
// smooth lobes below and to the glass and mirror lobes (Lobes.under_coat).
//
// The coat lies on a normal of its own (CoatLobe.normal): the surface's, or its own
// normal map's (glTF's clearcoatNormalTexture), never the base's normal map. Its
// Fresnel weight and what it lets through are taken at wo's cosine to that normal.
// decisions/0043-clear-coat.md.

const float COAT_F0 = 0.04f;
const uint COAT_LOBE = 4u;  // its id in smooth_lobes.glsl

// Members in an order no other lobe record has (smooth_lobes.glsl says why).
struct CoatLobe {
    float weight;   // c times its Fresnel reflectance toward wo (0 from below)
    float alpha;    // its GGX width; 0: no coat
    float factor;   // c
    vec3 normal;    // the normal it lies on (normal_map.glsl coat_normal), unit
};

// The coat of m seen at cos(theta_o) = cos_o to its own normal, which the caller
// sets (material_lobes).
CoatLobe coat_lobe(Material m, float cos_o) {
    CoatLobe l;
    l.factor = HAS_COAT && m.ggx_alpha > 0.0f ? m.coat : 0.0f;
    l.alpha = l.factor > 0.0f ? m.coat_alpha : 0.0f;
    l.weight = l.factor > 0.0f && cos_o > 0.0f ? l.factor * fresnel_schlick(vec3(COAT_F0), cos_o).x : 0.0f;
    l.normal = vec3(0.0f, 0.0f, 1.0f);
    return l;
}

bool coat_present(CoatLobe l) {
    return HAS_COAT && l.factor > 0.0f;
}

// What the layers under the coat keep of the light they send toward cos(theta_o) =
// cos_o: 1 - c R_coat(cos_o); 1 without a coat.
float under_coat(CoatLobe l, float cos_o) {
    float kept = 1.0f;
    if (coat_present(l) && cos_o > 0.0f) {
        float r = COAT_F0 * ggx_albedo(cos_o, l.alpha) + (1.0f - COAT_F0) * ggx_table_lookup(GGX_SCHLICK_TABLE, cos_o, l.alpha);
        kept = 1.0f - l.factor * r;
    }
    return kept;
}

// The ratio of cosines coat_eval scales by is bounded by taking the shading normal's
// cosine as at least this: a direction that grazes the shading surface then gives a
// hair less than its due, never an infinite value.
const float MIN_COAT_SHADING_COSINE = 1.0e-6f;

// The coat's value where the others' is taken on the shading normal n: the caller
// weighs every lobe by cos(theta_i) to n, and the coat's cosine is to its own
// normal, so where the two differ (a normal map bends one of them) its value is
// scaled by their ratio; where they are the same normal it is its GGX value as is.
vec3 coat_eval(CoatLobe l, vec3 n, vec3 wo, vec3 wi) {
    vec3 f = l.factor * ggx_eval(vec3(COAT_F0), 1.0f, l.alpha, l.normal, wo, wi);
    if (any(notEqual(l.normal, n))) {
        float ci = dot(n, wi);
        f *= ci > 0.0f ? max(dot(l.normal, wi), 0.0f) / max(ci, MIN_COAT_SHADING_COSINE) : 0.0f;
    }
    return f;
}

// Drawn and weighed on the coat's own normal, whichever frame the other lobes use.
float coat_pdf(CoatLobe l, Basis /* frame */, vec3 wo, vec3 wi, uint /* hemisphere */) {
    return ggx_pdf(l.alpha, l.normal, wo, wi);
}

vec3 coat_sample(CoatLobe l, Basis frame, vec3 wo, uint /* hemisphere */, float u1, float u2) {
    Basis own = frame;
    if (any(notEqual(l.normal, frame.n))) {
        own = basis_around(l.normal);
    }
    vec3 local = vec3(dot(wo, own.t), dot(wo, own.b), dot(wo, own.n));
    return from_basis(own, ggx_sample(l.alpha, local, u1, u2));
}
