// The rough lobe: GGX microfacet reflection, of the metallic-roughness material
// (bsdf.glsl), isotropic, in the local frame of the shading normal (z up):
//
//   f(wo, wi) = F(wo.h) D(h) G2(wo, wi) / (4 cos(theta_o) cos(theta_i)),  h = |wo + wi|
//
// D is the GGX (Trowbridge-Reitz) distribution of normals and G2 Smith's
// height-correlated masking-shadowing (Walter et al., "Microfacet Models for
// Refraction through Rough Surfaces", 2007; Heitz, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", 2014); F is Schlick's
// approximation of the Fresnel reflectance around the colour at normal incidence f0
// (fresnel.glsl).
// Light that scatters more than once between microfacets is not followed, so a
// white rough lobe reflects less than all the light (its test measures how much).
//
// Directions are drawn from the distribution of normals visible from wo (Heitz,
// "Sampling the GGX Distribution of Visible Normals", JCGT 2018), whose density over
// wi is D(h) G1(wo) / (4 cos(theta_o)): the sample's weight f cos(theta_i) / pdf is
// then F G2 / G1(wo), never larger than F.
//
// Its arithmetic is `precise` (no fused multiply-add): near the mirror direction of
// a smooth lobe D's denominator is a difference of nearly equal numbers, where a
// fused and an unfused rounding differ in the leading digits, and the two backends
// must agree (a sun reflected in smooth gold shows the difference).

// D(h) for cos(theta_h) = c: alpha^2 / (pi ((alpha^2 - 1) c^2 + 1)^2).
float ggx_d(float c, float alpha) {
    float a2 = alpha * alpha;
    precise float k = (a2 - 1.0f) * (c * c) + 1.0f;
    precise float d = a2 / (PI * k * k);
    return d;
}

// Smith's Lambda for a direction at cos(theta) = c: (sqrt(1 + alpha^2 tan^2) - 1) / 2,
// written without the difference of nearly equal numbers that loses it near the pole.
float ggx_lambda(float c, float alpha) {
    precise float c2 = c * c;
    precise float a2t2 = alpha * alpha * max(0.0f, 1.0f - c2) / c2;
    precise float lambda = a2t2 / (2.0f * (sqrt(1.0f + a2t2) + 1.0f));
    return lambda;
}

// The lobe's value f for unit directions wo, wi about the unit normal n (0 where
// either lies below).
// One return, no early exit, as for ggx_pdf: such functions the host inlines
// (host/gpu/spirv_specialize.cpp).
vec3 ggx_eval(vec3 f0, float f90, float alpha, vec3 n, vec3 wo, vec3 wi) {
    precise float co = dot(n, wo);
    precise float ci = dot(n, wi);
    precise vec3 f = vec3(0.0f);
    if (co > 0.0f && ci > 0.0f) {
        vec3 h = unit_vector(wo + wi);
        precise float oh = dot(wo, h);
        precise float nh = dot(n, h);
        precise float g2 = 1.0f / (1.0f + ggx_lambda(co, alpha) + ggx_lambda(ci, alpha));
        f = fresnel_schlick(f0, f90, oh) * (ggx_d(nh, alpha) * g2 / (4.0f * co * ci));
    }
    return f;
}

// The density over solid angle with which ggx_sample draws wi.
float ggx_pdf(float alpha, vec3 n, vec3 wo, vec3 wi) {
    precise float co = dot(n, wo);
    precise float ci = dot(n, wi);
    precise float pdf = 0.0f;
    if (co > 0.0f && ci > 0.0f) {
        vec3 h = unit_vector(wo + wi);
        precise float nh = dot(n, h);
        precise float g1 = 1.0f / (1.0f + ggx_lambda(co, alpha));
        pdf = ggx_d(nh, alpha) * g1 / (4.0f * co);
    }
    return pdf;
}

// Draws a local microfacet normal (z along the normal) visible from local wo (wo.z > 0),
// with density D(m) G1(wo) max(0, wo.m) / cos(theta_o): the view is stretched to the
// distribution of alpha = 1, where visible normals are a disc's projection onto the
// hemisphere, the disc is warped by the fraction of it the view sees, and the
// normal is unstretched.
vec3 ggx_visible_normal(float alpha, vec3 wo, float u1, float u2) {
    vec3 v = unit_vector(vec3(alpha * wo.x, alpha * wo.y, wo.z));
    float len2 = v.x * v.x + v.y * v.y;
    vec3 t1 = len2 > 0.0f ? vec3(-v.y, v.x, 0.0f) / sqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
    vec3 t2 = cross(v, t1);
    float r = sqrt(u1);
    vec2 sc = sin_cos(2.0f * PI * u2);
    float p1 = r * sc.y;
    float s = 0.5f * (1.0f + v.z);
    precise float p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * (r * sc.x);
    precise vec3 n = p1 * t1 + p2 * t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
    return unit_vector(vec3(alpha * n.x, alpha * n.y, max(0.0f, n.z)));
}

// Draws local wi for local wo (wo.z > 0): wo mirrored about a visible normal. wi may
// lie below the surface (the caller ends the path).
vec3 ggx_sample(float alpha, vec3 wo, float u1, float u2) {
    vec3 m = ggx_visible_normal(alpha, wo, u1, u2);
    precise vec3 wi = (2.0f * dot(wo, m)) * m - wo;
    return wi;
}

// The lobe as bsdf.glsl mixes it: the material's GGX factors (HAS_MICROFACET; alpha 0:
// no such lobe) and its selection weight seen from cos(theta_o) = cos_o, the mean of
// the Fresnel reflectance toward wo (0 from below). Its members are not in the order
// of GlossyLobe's, whose types they share (smooth_lobes.glsl says why that matters).
struct GgxLobe {
    float alpha;
    vec3 f0;
    float f90;
    float weight;
};

GgxLobe ggx_lobe(Material m, float cos_o) {
    GgxLobe l;
    l.alpha = HAS_MICROFACET ? m.ggx_alpha : 0.0f;
    l.f0 = l.alpha > 0.0f ? m.ggx_f0 : vec3(0.0f);
    l.f90 = material_f90(m);
    l.weight = l.alpha > 0.0f && cos_o > 0.0f ? mean3(fresnel_schlick(l.f0, l.f90, cos_o)) : 0.0f;
    return l;
}

bool ggx_present(GgxLobe l) {
    return HAS_MICROFACET && l.alpha > 0.0f;
}

// The mixture's interface (smooth_lobes.glsl), over the functions above.
vec3 ggx_eval(GgxLobe l, vec3 n, vec3 wo, vec3 wi) {
    return ggx_eval(l.f0, l.f90, l.alpha, n, wo, wi);
}

float ggx_pdf(GgxLobe l, Basis frame, vec3 wo, vec3 wi, uint /* hemisphere */) {
    return ggx_pdf(l.alpha, frame.n, wo, wi);
}

vec3 ggx_sample(GgxLobe l, Basis frame, vec3 wo, uint /* hemisphere */, float u1, float u2) {
    vec3 local = vec3(dot(wo, frame.t), dot(wo, frame.b), dot(wo, frame.n));
    return from_basis(frame, ggx_sample(l.alpha, local, u1, u2));
}
