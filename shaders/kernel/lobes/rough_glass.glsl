// Rough glass (glass.glsl, GlassLobe.alpha > 0; HAS_ROUGH_GLASS): the interface is a
// surface of GGX microfacets, each a smooth interface (Walter et al., "Microfacet
// Models for Refraction through Rough Surfaces", 2007). A scattering event draws a
// microfacet normal m visible from wo (ggx.glsl), splits there by the exact Fresnel
// reflectance as the smooth glass does (refract_fresnel; with a specular layer, by
// the layer's, glass.glsl glass_split), and the drawn direction
// wi takes G2(wo, wi) / G1(wo), what single scattering keeps of it, with Smith's
// height-correlated G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (for transmission too,
// the common approximation of Heitz 2014's form).
//
// Light that meets more than one microfacet is given back by dividing that weight by
// the interface's single-scattering albedo E(mu_o, alpha, eta), the weight's mean over
// the drawn directions (Turquin, "Practical multiple scattering compensation for
// microfacet models", 2019): a white rough interface then keeps all the light, in
// the shape of its single scattering (decision 0045). E of a solid interface comes
// from a table the host builds from rough_crossing itself
// (host/flatten/rough_glass_albedo.cpp); a thin wall's is the GGX lobe's E (below).
//
// The lobe is drawn, never light-sampled: next-event estimation and multiple
// importance sampling see it as they see the delta glass (global.glsl).

// What the interface does with wo (local, z along the shading normal, wo.z > 0) at
// the microfacet drawn by (u1, u2), both ways: the caller picks one with the Fresnel
// reflectance's probability. eta = n_incident / n_transmitted. A thin wall sends
// the transmitted light on as the reflection about m mirrored through the surface's
// plane: its two faces, parallel, turn the light back to its course but for the blur.
struct RoughCrossing {
    vec3 reflected;        // wo mirrored about m
    vec3 refracted;        // the transmitted direction; zero when totally reflected
    float reflectance;     // the Fresnel reflectance at m, 1 when totally reflected
    float reflect_weight;  // G2 / G1(wo) of the reflected direction; 0 when it lies below
    float refract_weight;  // the same of the transmitted one; 0 when it lies above
};

RoughCrossing rough_crossing(float alpha, float eta, bool thin, vec3 wo, float u1, float u2) {
    vec3 m = ggx_visible_normal(alpha, wo, u1, u2);
    Refraction r = refract_fresnel(-wo, m, eta);
    RoughCrossing c;
    precise vec3 reflected = (2.0f * dot(wo, m)) * m - wo;
    c.reflected = reflected;
    c.refracted = thin ? vec3(reflected.x, reflected.y, -reflected.z) : r.dir;
    c.reflectance = r.reflectance;
    precise float kept_o = 1.0f + ggx_lambda(wo.z, alpha);
    c.reflect_weight = reflected.z > 0.0f ? kept_o / (kept_o + ggx_lambda(reflected.z, alpha)) : 0.0f;
    c.refract_weight =
        !r.total && c.refracted.z < 0.0f ? kept_o / (kept_o + ggx_lambda(-c.refracted.z, alpha)) : 0.0f;
    return c;
}

// The table of a solid interface's E, after the GGX tables (and the sheen's with
// HAS_SHEEN; ggx_albedo.glsl): one per knot of log(eta) (constants.glsl), each of knots
// laid out as those are, without means.
const uint ROUGH_GLASS_KNOT_WORDS = GGX_TABLE_SIZE * GGX_TABLE_SIZE;

uint rough_glass_table() {
    return HAS_SHEEN ? SHEEN_TABLE + GGX_SCHLICK_TABLE : SHEEN_TABLE;
}

// The knot coordinate of eta in [0, 1].
float rough_glass_eta_coordinate(float eta) {
    return 0.5f + 0.5f * log(eta) / log(ROUGH_GLASS_ETA_MAX);
}

// The value at (mu_o, alpha, eta) of the set of knot tables starting at `first`:
// linear in log(eta) between the tables of two knots.
float rough_glass_lookup(uint first, float mu, float alpha, float eta) {
    float s = clamp(rough_glass_eta_coordinate(eta), 0.0f, 1.0f) * float(ROUGH_GLASS_ETA_KNOTS - 1u);
    uint k = min(uint(s), ROUGH_GLASS_ETA_KNOTS - 2u);
    uint table = first + k * ROUGH_GLASS_KNOT_WORDS;
    return mix(ggx_table_lookup(table, mu, alpha), ggx_table_lookup(table + ROUGH_GLASS_KNOT_WORDS, mu, alpha),
               s - float(k));
}

// E(mu_o, alpha, eta) from its table. A thin wall's E is the GGX lobe's with a
// Fresnel of 1: its two directions have the same weight and lie on opposite sides
// together, so the Fresnel split drops out of the mean, which is then the
// reflection's alone, as ggx_albedo.cpp integrates it (a specular layer changes
// nothing there).
float rough_glass_albedo(float mu, float alpha, float eta, bool thin) {
    return thin ? ggx_albedo(mu, alpha) : rough_glass_lookup(rough_glass_table(), mu, alpha, eta);
}

// A solid interface's E under a specular layer (glass.glsl glass_split). Off total
// internal reflection the layer reflects with p = a + b R instead of R, its largest
// channel written out: with g = f0 / (1 - f0) and T the largest channel of its tint,
// a = factor (T - 1) g and b = factor (1 - (T - 1) g). Its mean over the microfacets
// is then E + a D1 + (b - 1) DR, with D1 the mean of the two ways' difference
// G2/G1(reflected) - G2/G1(transmitted) and DR that times R: two more sets of tables
// after E's, which the host appends for a scene whose glass has a layer
// (rough_glass_albedo.cpp). (Where the layer is clamped to 1, p is not linear; E is
// then only near.)
float rough_glass_layered_albedo(float e, GlassLobe glass, float mu, float eta) {
    float f0 = interface_f0(eta);
    float lift = (max3(glass.layer_tint) - 1.0f) * (f0 / (1.0f - f0));
    float a = glass.layer_f90 * lift;
    float b = glass.layer_f90 * (1.0f - lift);
    uint d1 = rough_glass_table() + ROUGH_GLASS_ETA_KNOTS * ROUGH_GLASS_KNOT_WORDS;
    return e + a * rough_glass_lookup(d1, mu, glass.alpha, eta) +
           (b - 1.0f) * rough_glass_lookup(d1 + ROUGH_GLASS_ETA_KNOTS * ROUGH_GLASS_KNOT_WORDS, mu, glass.alpha, eta);
}

// E is floored here: a weight of 1 / E stays bounded where a view along the surface
// leaves few drawn directions above it.
const float MIN_ROUGH_GLASS_ALBEDO = 0.05f;

// The ray leaving rough glass at a hit seen along ray.dir, through an interface of
// index ratio eta (eta != 1): reflected with the Fresnel reflectance's probability
// (`split`, uniform in [0, 1)), transmitted otherwise, at the microfacet that `u`
// draws. The throughput takes the glass's colour for that way times `scale` (the
// group's selection) times G2 / G1 / E; a direction on the wrong side of the
// geometric surface takes 0 and ends the path (path_sample). A solid body's
// transmission updates the media the path is in, as the smooth glass's does.
// One return, no early exit: such functions the host inlines (host/gpu/spirv_specialize.cpp).
Ray rough_glass_scatter(Ray ray, Hit hit, vec3 p, GlassLobe glass, float eta, float split, vec2 u, float scale,
                        INOUT(vec3) beta, INOUT(uvec4) media) {
    Basis frame = basis_around(hit.normal);
    vec3 wo = -ray.dir;
    // A shading normal may turn from the view; the interface is then seen edge-on.
    vec3 local = vec3(dot(wo, frame.t), dot(wo, frame.b), max(dot(wo, frame.n), 1e-6f));
    RoughCrossing c = rough_crossing(glass.alpha, eta, glass.thin, local, u.x, u.y);
    GlassSplit layer = glass_split(glass, c.reflectance, eta);
    bool reflects = split < layer.p_reflect;
    note_decision(reflects ? DECISION_GLASS_REFLECTS : DECISION_GLASS_REFRACTS);
    vec3 dir = unit_vector(from_basis(frame, reflects ? c.reflected : c.refracted));
    float side = reflects ? dot(dir, hit.geo_normal) : -dot(dir, hit.geo_normal);
    float kept = side > 0.0f ? (reflects ? c.reflect_weight : c.refract_weight) : 0.0f;
    float e = rough_glass_albedo(local.z, glass.alpha, eta, glass.thin);
    if (HAS_DIELECTRIC_SPECULAR && glass.layered && !glass.thin) {
        e = rough_glass_layered_albedo(e, glass, local.z, eta);
    }
    e = max(e, MIN_ROUGH_GLASS_ALBEDO);
    beta *= (reflects ? glass.reflected * layer.tint : glass.color) * (scale * kept / e);
    if (!reflects && !glass.thin) {
        media = media_after_refraction(media, hit.material, hit.front_face);
    }
    return Ray(offset_ray_origin(p, reflects ? hit.geo_normal : -hit.geo_normal), dir);
}
