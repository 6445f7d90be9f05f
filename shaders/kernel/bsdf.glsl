// The surface model of global mode (global.glsl): a material is a sum of lobes, each
// in a file of its own under lobes/:
//
//   diffuse  kd * diffuse / pi                     Lambertian (diffuse.glsl)
//   glossy   ks * specular, normalized Phong       (glossy.glsl)
//   ggx      GGX microfacet reflection             metallic-roughness (ggx.glsl)
//   coat     a clear coat over the others          metallic-roughness (coat.glsl)
//   sheen    cloth's sheen, under the coat         metallic-roughness (sheen.glsl)
//   mirror   reflect                               a delta lobe (mirror.glsl)
//   glass    transmit, split by Fresnel            delta lobes (glass.glsl), or drawn at a
//                                                  GGX microfacet when rough (rough_glass.glsl)
//
// A metallic-roughness material (HAS_MICROFACET) has the diffuse and the ggx lobes
// only, the diffuse one coupled to the ggx one so that their sum stays at most 1
// (diffuse.glsl), and with transmission glass: the glass lobe carries glass_share of
// the material (texture.glsl), the smooth lobes the rest (Lobes.smooth_share). Sheen
// lies over all of them and a clear coat over that: the layers under each keep what
// it lets through toward wo (SheenLobe.keep, Lobes.under_coat).
//
// A scattering event picks one lobe group at random in proportion to its weight:
// the smooth group (the lobes of lobes/smooth_lobes.glsl, sampled together as a
// mixture, each in proportion to its own weight), the mirror or the glass. Dividing
// by the chosen group's probability keeps the estimate unbiased; next-event
// estimation and multiple importance sampling (global.glsl) apply to the smooth group
// only, as no light sample can land on a delta lobe (nor is one taken for rough glass).

struct Lobes {
#define SMOOTH_LOBE(id, name, Type, FEATURE) Type name;
#include "lobes/smooth_lobes.glsl"
    MirrorLobe mirror;
    GlassLobe glass;
    float smooth_share;  // the share of the material the smooth lobes carry (1 but beside glTF's glass)
    float under_coat;    // what the coat lets through toward wo of the other lobes' light (coat.glsl; 1: no coat)
};

// The lobes of material m seen from wo (unit, away from the surface) at a hit whose
// shading normal is n and whose clear coat lies on coat_n (normal_map.glsl): some
// lobes' selection weights depend on wo's cosine to their normal.
Lobes material_lobes(Material m, vec3 n, vec3 coat_n, vec3 wo) {
    float cos_o = dot(n, wo);
    float coat_cos_o = dot(coat_n, wo);
    Lobes l;
#define SMOOTH_LOBE(id, name, Type, FEATURE) l.name = name##_lobe(m, id == COAT_LOBE ? coat_cos_o : cos_o);
#include "lobes/smooth_lobes.glsl"
    l.coat.normal = coat_n;
    l.mirror = mirror_lobe(m);
    l.glass = glass_lobe(m);
    l.smooth_share = 1.0f - glass_share(m);
    l.under_coat = under_coat(l.coat, coat_cos_o);
    // What the layers leave the base toward wo: its selection weights and the glass's
    // and mirror's colours take it here, the smooth lobes' values in eval_smooth.
    float under = HAS_SHEEN ? l.under_coat * l.sheen.keep : l.under_coat;
    if ((HAS_COAT || HAS_SHEEN) && under < 1.0f) {
#define SMOOTH_LOBE(id, name, Type, FEATURE) if (id != COAT_LOBE && id != SHEEN_LOBE) l.name.weight *= under;
#include "lobes/smooth_lobes.glsl"
        l.mirror.color *= under;
        l.mirror.weight *= under;
        l.glass.color *= under;
        l.glass.reflected *= under;
        l.glass.weight *= under;
    }
    if (HAS_SHEEN && HAS_COAT) {
        l.sheen.weight *= l.under_coat;
    }
#define SMOOTH_LOBE(id, name, Type, FEATURE) CHECK(is_finite_bits(l.name.weight) && l.name.weight >= 0.0f);
#include "lobes/smooth_lobes.glsl"
    return l;
}

// The sum of the smooth lobes' weights, which share out the group's draws.
float smooth_sum(Lobes l) {
    float w = 0.0f;
#define SMOOTH_LOBE(id, name, Type, FEATURE) if (FEATURE) w += l.name.weight;
#include "lobes/smooth_lobes.glsl"
    return w;
}

// The smooth group's weight among the groups: that sum times the group's share, the
// layers' whole (they lie over the glass too).
float smooth_weight(Lobes l) {
    float w = l.smooth_share * smooth_sum(l);
    if (HAS_COAT) {
        w += (1.0f - l.smooth_share) * l.coat.weight;
    }
    if (HAS_SHEEN) {
        w += (1.0f - l.smooth_share) * l.sheen.weight;
    }
    return w;
}

float lobes_total(Lobes l) {
    return smooth_weight(l) + l.mirror.weight + l.glass.weight;
}

// The smooth lobes' BSDF value for light from wi leaving toward wo (both unit,
// pointing away from the surface; n the shading normal on their side).
vec3 eval_smooth(Lobes l, vec3 n, vec3 wo, vec3 wi) {
    vec3 f = vec3(0.0f);
    vec3 coat = vec3(0.0f);
    vec3 sheen = vec3(0.0f);
#define SMOOTH_LOBE(id, name, Type, FEATURE)                \
    if (FEATURE && name##_present(l.name)) {                \
        if (id == COAT_LOBE) {                              \
            coat = name##_eval(l.name, n, wo, wi);          \
        } else if (id == SHEEN_LOBE) {                      \
            sheen = name##_eval(l.name, n, wo, wi);         \
        } else {                                            \
            f += name##_eval(l.name, n, wo, wi);            \
        }                                                   \
    }
#include "lobes/smooth_lobes.glsl"
    f *= l.smooth_share;
    if (HAS_SHEEN) {
        f = f * l.sheen.keep + sheen;
    }
    if (HAS_COAT) {
        f = f * l.under_coat + coat;
    }
    CHECK(is_weight(f));
    return f;
}

// The density over solid angle with which sample_smooth draws wi: the lobes'
// densities mixed in proportion to their weights.
float pdf_smooth(Lobes l, Basis frame, vec3 wo, vec3 wi, uint hemisphere) {
    float w = smooth_sum(l);
    if (!(w > 0.0f)) {
        return 0.0f;
    }
    float pdf = 0.0f;
#define SMOOTH_LOBE(id, name, Type, FEATURE)                                              \
    if (FEATURE && l.name.weight > 0.0f) {                                       \
        pdf += l.name.weight * name##_pdf(l.name, frame, wo, wi, hemisphere);    \
    }
#include "lobes/smooth_lobes.glsl"
    CHECK(is_finite_bits(pdf) && pdf >= 0.0f);
    return pdf / w;
}

// Draws wi from the smooth group: u0 picks a lobe in proportion to its weight (the
// last lobe of nonzero weight whose share starts at or below u0 times the group's
// weight, so a pick rounded up to the end still lands on a lobe that can be drawn),
// (u1, u2) the direction. The result may point below the surface (the caller ends
// the path there: the lobes are zero on that side).
vec3 sample_smooth(Lobes l, Basis frame, vec3 wo, uint hemisphere, float u0, float u1, float u2) {
    float pick = u0 * smooth_sum(l);
    uint chosen = 0u;
    float start = 0.0f;
#define SMOOTH_LOBE(id, name, Type, FEATURE) \
    if (FEATURE && l.name.weight > 0.0f) { \
        if (pick >= start) {        \
            chosen = id;            \
        }                           \
        start += l.name.weight;     \
    }
#include "lobes/smooth_lobes.glsl"
#define SMOOTH_LOBE(id, name, Type, FEATURE)                                            \
    if (FEATURE && chosen == id) {                                             \
        return name##_sample(l.name, frame, wo, hemisphere, u1, u2);           \
    }
#include "lobes/smooth_lobes.glsl"
    return vec3(0.0f);
}
