// The sheen of a metallic-roughness material (glTF's KHR_materials_sheen): the soft
// back-scattering of cloth and velvet, a microfacet lobe of the "Charlie" distribution
// of normals (Estevez and Kulla, "Production Friendly Microfacet Sheen BRDF", 2017),
//
//   D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi),
//
// with Ashikhmin's visibility term 1 / (4 (cos_i + cos_o - cos_i cos_o)) (Neubelt and
// Pettineo, "Crafting a Next-Gen Material Pipeline for The Order: 1886", 2013), times
// the sheen colour. alpha is the square of the sheen roughness. Like the clear coat
// (coat.glsl) it lies over the rest of the material, which keeps
//
//   1 - max(sheen colour) E_sheen(mu_o)
//
// of the light it sends toward the viewer, E_sheen the lobe's albedo with a colour of
// 1 from the tables (ggx_albedo.glsl: the host integrates this file's sheen_value), so
// that a white base under a white sheen reflects all the light and no more. Drawn from
// the cosine-weighted hemisphere: the lobe is broad, its peak at grazing half vectors.
// decisions/0044-sheen.md.

const uint SHEEN_LOBE = 5u;  // its id in smooth_lobes.glsl

// f / colour for unit wo, wi about the unit normal n (0 where either lies below).
float sheen_value(float alpha, vec3 n, vec3 wo, vec3 wi) {
    float co = dot(n, wo);
    float ci = dot(n, wi);
    float f = 0.0f;
    if (co > 0.0f && ci > 0.0f) {
        vec3 h = unit_vector(wo + wi);
        float c = clamp(dot(n, h), 0.0f, 1.0f);
        float sin2 = max(0.0f, 1.0f - c * c);
        float inv = 1.0f / alpha;
        float d = (2.0f + inv) * pow(sin2, 0.5f * inv) * (0.5f / PI);
        f = d / (4.0f * (ci + co - ci * co));
    }
    return f;
}

// Members in an order no other lobe record has (smooth_lobes.glsl says why).
struct SheenLobe {
    vec3 color;     // the sheen colour; 0: no sheen
    float weight;   // its albedo toward wo, mean over the colours
    float alpha;
    float keep;     // what the layers under it keep toward wo: 1 - max(colour) E_sheen(mu_o)
};

SheenLobe sheen_lobe(Material m, float cos_o) {
    SheenLobe l;
    l.color = HAS_SHEEN && m.ggx_alpha > 0.0f ? m.sheen_color : vec3(0.0f);
    l.alpha = m.sheen_alpha;
    l.weight = 0.0f;
    l.keep = 1.0f;
    if (max3(l.color) > 0.0f && cos_o > 0.0f) {
        float e = ggx_table_lookup(SHEEN_TABLE, cos_o, l.alpha);
        l.weight = mean3(l.color) * e;
        // The albedo passes 1 toward grazing for narrow distributions (Ashikhmin's
        // visibility does not conserve energy there): the layers under it then get nothing.
        l.keep = max(0.0f, 1.0f - max3(l.color) * e);
    }
    return l;
}

bool sheen_present(SheenLobe l) {
    return HAS_SHEEN && max3(l.color) > 0.0f;
}

vec3 sheen_eval(SheenLobe l, vec3 n, vec3 wo, vec3 wi) {
    return l.color * sheen_value(l.alpha, n, wo, wi);
}

float sheen_pdf(SheenLobe, Basis frame, vec3 /* wo */, vec3 wi, uint /* hemisphere */) {
    return max(dot(wi, frame.n), 0.0f) * (1.0f / PI);
}

vec3 sheen_sample(SheenLobe, Basis frame, vec3 /* wo */, uint /* hemisphere */, float u1, float u2) {
    return from_basis(frame, sample_hemisphere(HEMISPHERE_COSINE, u1, u2));
}
