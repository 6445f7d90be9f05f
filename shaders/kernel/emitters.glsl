// Points on the area lights: the emissive primitives of the Emitter list
// (layout.glsl; built by host/flatten/flat_scene.cpp). An emitter is picked with
// probability proportional to its power, area times mean emitted radiance, so a
// bright small lamp is not starved by a dim large one. Then a point on it: through
// the solid angle it covers where that can be drawn (solid_angle.glsl: a sphere's
// cone, a rectangle's spherical rectangle), else uniformly on its area. Picked so,
// a point of an emitter of mean radiance w has density w / emitter_power() over
// the emitting area, whichever emitter it lies on. A triangle with an emission
// texture is an emitter only where its own footprint in the texture emits, picked by
// its mean radiance over that footprint (triangle_emitter_weight), and sampled
// uniformly as any other; the estimate takes the textured radiance at the point
// drawn, over that density: unbiased, since the host counts a footprint black only
// where every texel the triangle's filtered look-ups can reach is black. What is
// particular to a kind of primitive lives in its file (shapes/kinds.glsl).
//
// Every draw takes exactly one slot (rng.glsl), whatever it picks: both backends then
// consume identical streams, and the numbers a sample draws after a light sample do
// not depend on which emitter that sample chose.

// The first emitter whose cumulative power fraction exceeds u in [0, 1). The last
// fraction is exactly 1, so there always is one.
uint pick_emitter(float u) {
    uint lo = 0u;
    uint hi = emitter_count() - 1u;
    loop_enter();
    while (lo < hi) {
        if (!loop_tick()) {
            break;  // the sample is flagged truncated; any index in range will do
        }
        uint mid = (lo + hi) / 2u;
        if (u < load_emitter(mid).cdf.x) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// A point uniform by area on the emitter, from two uniform numbers.
EmitterPoint emitter_point(Emitter e, float u1, float u2) {
    uint kind = e.prim.x >> REF_KIND_SHIFT;
    uint index = e.prim.x & REF_INDEX_MASK;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    if (HAS_##NAMES && kind == REF_##NAME) {                      \
        return name##_emitter_point(index, e.prim.y, u1, u2);     \
    }
#include "shapes/kinds.glsl"
    // Not reached for a list the host built; a zero normal faces nothing, so the
    // estimator skips the point.
    return EmitterPoint(vec3(0.0f), vec3(0.0f), vec3(0.0f), 0.0f);
}

// The density over solid angle at o of a point y on an emitter drawn uniformly by
// area, with its density over area.
float area_to_solid_angle(float area_density, vec3 o, vec3 y, vec3 normal) {
    vec3 to_light = y - o;
    float r2 = dot(to_light, to_light);
    float cos_emitter = -dot(normal, to_light) / sqrt(r2);
    return cos_emitter > 0.0f ? min(area_density * r2 / cos_emitter, INFINITY_T) : 0.0f;
}

// One light sample for a point at o, from one slot: its first number picks the
// emitter and, rescaled to that emitter's share of [0, 1), places the point with the
// second. The samples of a pixel that pick one emitter are then those of the slot's
// Sobol points whose first number falls in that share, and such a subset of a net,
// rescaled, is a net again: each emitter's points stay stratified. (With the choice
// in a slot of its own, each emitter got a random subset of the points, spread no
// better than independent ones.) u is the slot's two numbers.
LightSample sample_light_from(vec3 o, vec2 u) {
    Emitter e = load_emitter(pick_emitter(u.x));
    // The largest float below 1 bounds it: rounding may bring the quotient up to 1.
    u.x = min((u.x - e.cdf.y) / (e.cdf.x - e.cdf.y), 0.99999994f);
    uint kind = e.prim.x >> REF_KIND_SHIFT;
    uint index = e.prim.x & REF_INDEX_MASK;
    LightSample drawn = LightSample(vec3(0.0f), vec3(0.0f), vec3(0.0f), 0.0f);
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)                       \
    if (HAS_##NAMES && kind == REF_##NAME && name##_light_sample(o, index, u, drawn)) { \
        return drawn;                                                                   \
    }
#include "shapes/kinds.glsl"
    EmitterPoint y = emitter_point(e, u.x, u.y);
    float density = y.weight / emitter_power();
    return LightSample(y.position, y.normal, y.emission, area_to_solid_angle(density, o, y.position, y.normal));
}

LightSample sample_light(vec3 o, INOUT(Rng) rng) {
    return sample_light_from(o, rng_2d(rng));
}

// The density over solid angle with which sample_light, called at the ray's origin,
// draws the direction of a ray that hit an emitter's front face (for multiple
// importance sampling): the same choice of technique, from the same point, and the
// same density, from the emitter's weight rather than the radiance at the hit.
float light_pdf_of_hit(Ray ray, Hit hit) {
    uint kind = hit.prim >> REF_KIND_SHIFT;
    uint index = hit.prim & REF_INDEX_MASK;
    Material m = load_material(hit.material);
    float weight = 0.0f;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    if (HAS_##NAMES && kind == REF_##NAME) {                      \
        weight = name##_pick_weight(index, m);                    \
    }
#include "shapes/kinds.glsl"
    float area_density = weight / emitter_power();
    float pdf = 0.0f;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS)                                      \
    if (HAS_##NAMES && kind == REF_##NAME && name##_light_pdf(ray.origin, index, area_density, pdf)) { \
        return pdf;                                                                                    \
    }
#include "shapes/kinds.glsl"
    // geo_normal faces the ray, so this is the emitting face's cosine.
    float cos_emitter = -dot(hit.geo_normal, ray.dir);
    return min(area_density * hit.t * hit.t / cos_emitter, INFINITY_T);
}
