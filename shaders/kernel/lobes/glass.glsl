// The glass lobe: delta reflection and refraction at a smooth interface, split by the
// exact Fresnel reflectance (or all refracted with "fresnel": false), and the stack of
// media a ray travels in. `n` is the unit shading normal on the side the ray arrives
// from (Hit.normal), `d` the unit direction of the arriving ray.

struct GlassLobe {
    vec3 color;      // what the refracted light takes: transmit (0 without HAS_REFRACTION)
    float ior;
    vec3 reflected;  // what the reflected light takes: the same colour for the paper's glass
    bool fresnel;    // split by Fresnel; otherwise refracted unless totally reflected
    bool thin;       // a thin wall: the refracted light goes on straight, in the same medium
    float weight;    // the lobe's selection weight: the mean of its colour, or its share
    float alpha;     // GGX width of rough glass (rough_glass.glsl); 0: smooth
    bool layered;      // glTF's specular layer changes the reflectance (glass_split below)
    vec3 layer_tint;   // its colour: its reflectance at normal incidence over the ior's
    float layer_f90;   // its factor: its reflectance at grazing incidence
};

// The paper's glass tints what it reflects and refracts alike by `transmit`. A
// metallic-roughness material's glass is glTF's (KHR_materials_transmission): it
// reflects glass_share untinted and refracts glass_share times the base colour
// (texture.glsl, set_metallic_roughness), and is rough with the material's GGX width
// above MIN_GGX_ALPHA (HAS_ROUGH_GLASS; rough_glass.glsl).
GlassLobe glass_lobe(Material m) {
    GlassLobe l;
    l.color = HAS_REFRACTION ? m.transmit : vec3(0.0f);
    l.ior = m.ior;
    l.reflected = l.color;
    l.fresnel = m.fresnel != 0u;
    l.thin = false;
    l.weight = mean3(l.color);
    l.alpha = 0.0f;
    l.layered = false;
    l.layer_tint = vec3(1.0f);
    l.layer_f90 = 1.0f;
    float share = glass_share(m);
    if (share > 0.0f) {
        l.reflected = vec3(share);
        l.thin = m.thin_walled != 0u;
        l.weight = share;
        l.alpha = HAS_ROUGH_GLASS && m.ggx_alpha > MIN_GGX_ALPHA ? m.ggx_alpha : 0.0f;
        if (HAS_DIELECTRIC_SPECULAR) {
            float f0 = m.dielectric_f90 * m.dielectric_f0;
            l.layer_tint = f0 > 0.0f ? m.dielectric_f0_rgb / f0 : vec3(1.0f);
            l.layer_f90 = m.dielectric_f90;
            l.layered = m.dielectric_f90 != 1.0f || m.dielectric_f0_rgb != vec3(m.dielectric_f0);
        }
    }
    return l;
}

// How the glass splits light at an interface (or microfacet) of index ratio eta whose
// exact Fresnel reflectance is `reflectance`: reflected with probability p_reflect,
// the throughput then taking `tint` besides the glass's reflected colour, transmitted
// otherwise with nothing more.
struct GlassSplit {
    float p_reflect;
    vec3 tint;
};

// The reflectance at normal incidence of an interface of index ratio eta,
// ((1 - eta) / (1 + eta))^2, the same from either side.
float interface_f0(float eta) {
    float r0 = (1.0f - eta) / (1.0f + eta);
    return r0 * r0;
}

// glTF's specular layer on glass (KHR_materials_specular over _transmission;
// HAS_DIELECTRIC_SPECULAR, decision 0052). The extension writes the reflectance as
// F0 + (F90 - F0) w per channel, with F0 = min(f0 colour, 1) factor, F90 the factor
// and Schlick's w = (1 - cos)^5, and lets 1 - max(reflectance) through. vkrt's glass
// reflects by the exact Fresnel equations, so the layer here scales the interface's
// exact reflectance R: factor (R + (tint - 1) f0 (1 - R) / (1 - f0)), with f0 the
// interface's own reflectance at normal incidence, ((1 - eta) / (1 + eta))^2, and the
// tint min(f0 colour, 1) / f0 of the material's. That is the extension's form with w
// = (R - f0) / (1 - f0), how far R has risen from f0 toward 1: F0 at normal
// incidence, F90 at grazing, the exact glass for factor 1 and a white colour, and
// no reflection where there is no interface (nested glass of one ior). Reflecting
// with the largest channel's probability leaves the reflected way the tint
// layer / max and the transmitted way 1. Total internal reflection keeps all the
// light: there is no way through to give the rest to.
GlassSplit glass_split(GlassLobe glass, float reflectance, float eta) {
    GlassSplit s = GlassSplit(reflectance, vec3(1.0f));
    if (HAS_DIELECTRIC_SPECULAR && glass.layered && reflectance < 1.0f) {
        float f0 = interface_f0(eta);
        vec3 layer = glass.layer_f90 * (reflectance + (glass.layer_tint - 1.0f) * (f0 * (1.0f - reflectance) / (1.0f - f0)));
        layer = clamp(layer, vec3(0.0f), vec3(1.0f));
        s.p_reflect = max3(layer);
        s.tint = s.p_reflect > 0.0f ? layer / s.p_reflect : vec3(0.0f);
    }
    return s;
}

struct Refraction {
    vec3 dir;           // the refracted direction, unit length; zero when total
    float reflectance;  // the Fresnel reflectance R: the transmitted share is 1 - R
    bool total;         // total internal reflection: no refracted ray, R = 1
};

// Snell's law and the exact Fresnel equations for unpolarized light (the mean of the
// s- and p-polarized reflectances) at an interface with relative index eta =
// n_incident / n_transmitted. Exact rather than Schlick's approximation: it costs a
// handful of flops on a hit that already pays for a ray, and Schlick's error grows
// away from ior 1.5 and, on the denser side, needs the transmitted angle anyway.
// At and beyond the critical angle all energy is reflected.
// eta == 1 (an interface between equal indices, such as nested glass of one ior) is
// no interface at all: the ray goes on bit for bit and nothing reflects. Through the
// general formula cos_t = sqrt(cos_i^2) can miss cos_i by an ULP, leaving a tiny R
// and a turned ray at every crossing (and cos_i^2 underflows below 1e-19).
Refraction refract_fresnel(vec3 d, vec3 n, float eta) {
    if (eta == 1.0f) {
        return Refraction(d, 0.0f, false);
    }
    precise float cos_i = clamp(-dot(d, n), 0.0f, 1.0f);
    // cos^2(theta_t) = 1 - eta^2 (1 - cos_i^2), computed as (1 - eta)(1 + eta) +
    // (eta cos_i)^2: 1 - eta is exact for eta in [1/2, 2] (Sterbenz), so for an ior
    // near 1 and at grazing incidence no digit is lost to 1 - cos_i^2 rounding away
    // cos_i (the textbook form totally reflected grazing rays at eta 1 and was up to
    // 0.06 off in R near the critical angle); and for eta < 1 both terms are
    // positive, so a ray entering a denser medium is never totally reflected.
    precise float eta_cos_i = eta * cos_i;
    precise float cos2_t = (1.0f - eta) * (1.0f + eta) + eta_cos_i * eta_cos_i;
    if (!(cos2_t > 0.0f)) {
        return Refraction(vec3(0.0f), 1.0f, true);
    }
    precise float cos_t = sqrt(cos2_t);
    // Dividing the textbook forms by n_transmitted leaves only eta.
    precise float r_s = (eta_cos_i - cos_t) / (eta_cos_i + cos_t);
    precise float r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    precise vec3 t = eta * d + (eta_cos_i - cos_t) * n;
    precise float reflectance = 0.5f * (r_s * r_s + r_p * r_p);
    return Refraction(unit_vector(t), reflectance, false);
}

// The media a ray travels in, innermost first: the glass bodies it has entered
// through a front face and not yet left, four deep, each as 1 + the index of its
// material; 0 is an empty level, air (index of refraction 1, nothing absorbed), so
// that a zero uvec4 is a ray in air. Refraction through a front face pushes the
// body's material, through a back face pops it, and the interface then separates the
// index of refraction the ray is in from the one it goes to: nested glass of equal
// ior is an interface of eta 1, invisible, as it is in nature. A fifth nested body is
// remembered as air once the ray has left the four inside it.
float medium_ior(uint level) {
    return level > 0u ? load_material(level - 1u).ior : 1.0f;
}

uvec4 media_enter(uvec4 media, uint material) {
    return uvec4(material + 1u, media.x, media.y, media.z);
}

uvec4 media_leave(uvec4 media) {
    return uvec4(media.y, media.z, media.w, 0u);
}

// n_incident / n_transmitted at a hit on glass of index `ior`: through the front face
// from the ray's medium into the glass, through the back face from the glass into the
// medium outside it. A ray that never entered the body it leaves (an eye inside the
// glass) has air outside: 1 / ior and ior, as for a lone body in air.
float interface_eta(uvec4 media, float ior, bool front_face) {
    return front_face ? medium_ior(media.x) / ior : ior / medium_ior(media.y);
}

// The media of the ray refracted at a hit on `material`.
uvec4 media_after_refraction(uvec4 media, uint material, bool front_face) {
    return front_face ? media_enter(media, material) : media_leave(media);
}

// The fraction of light that crosses a distance t of the ray's medium: Beer and
// Lambert's exp(-sigma t) with the medium's attenuation coefficient sigma (per unit
// length, per channel; glTF's KHR_materials_volume, material_fields.glsl), 1 in air
// and without HAS_ABSORPTION. t is INFINITY_T for a ray that leaves the scene: an
// absorbing medium then lets nothing through, and a clear one (sigma 0) everything.
// One return, no early exit: such functions the host inlines (host/gpu/spirv_specialize.cpp).
vec3 medium_transmittance(uvec4 media, float t) {
    vec3 kept = vec3(1.0f);
    if (HAS_ABSORPTION && media.x != 0u) {
        vec3 sigma = load_material(media.x - 1u).attenuation;
        kept = vec3(sigma.x > 0.0f ? exp(-sigma.x * t) : 1.0f, sigma.y > 0.0f ? exp(-sigma.y * t) : 1.0f,
                    sigma.z > 0.0f ? exp(-sigma.z * t) : 1.0f);
    }
    return kept;
}
