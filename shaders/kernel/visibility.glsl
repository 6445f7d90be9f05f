// Whether light arriving along a direction reaches a hit: the one test that the
// scene's `lights` and area lights share, in local mode (shade.glsl,
// area_lights.glsl) and in global mode's next-event estimation (global.glsl).

// l is the unit direction from the hit toward the light point `light`, in
// homogeneous coordinates: w = 1 for a point, w = 0 for a directional light, which
// lies infinitely far along l. source_faces says whether the light sends light that
// way (an emitter's front faces the hit; always true for the scene's `lights`). The
// light counts only where both of the surface's normals face it (a shading normal
// alone would let light through a coarse mesh's silhouette), and, with shadows, where
// nothing lies in between: that costs one shadow ray, counted. A hit lifted toward
// its smooth surface (terminator.glsl) needs only the shading normal to face the
// light: its shadow ray, from the lifted point, decides, so the terminator follows
// the smooth surface, not the facets. Written as plain `> 0` tests so that a light
// exactly at the hit point (dist 0, l NaN) fails them. A flat emitter cannot light
// itself: l lies in its plane, so one of the cosines is at most a rounding error
// above 0.
// The shadow ray runs from shadow_origin, the hit moved off its surface, to `light`
// itself, not along l for the hit's distance: the move is a number of ULPs of the
// hit's coordinates, which far from the origin exceeds the margin SHADOW_RAY_END
// leaves before the light, and a ray of the hit's length from the moved origin then
// reached the emitter's own surface (the stability suite's scale cases found it). Toward a
// directional light, or the environment, the shadow ray runs along l without end:
// anything it meets blocks the light.
bool light_reaches(Hit hit, vec3 shadow_origin, vec3 l, vec4 light, bool source_faces, INOUT(uint) shadow_rays) {
    bool lifted = HAS_TERMINATOR && dot(hit.lift, hit.geo_normal) > 0.0f;
    bool faces = source_faces && dot(hit.normal, l) > 0.0f && (lifted || dot(hit.geo_normal, l) > 0.0f);
    note_decision(faces ? DECISION_LIGHT_FACING : DECISION_LIGHT_BEHIND);
    if (!faces) {
        return false;
    }
    if (HAS_SHADOWS) {
        shadow_rays += 1u;
        if ((HAS_DIRECTED_LIGHTS || HAS_ENVIRONMENT_MAP) && light.w == 0.0f) {
            return !occluded(Ray(shadow_origin, l), INFINITY_T);
        }
        // Shadow rays stop short of the light (SHADOW_RAY_END), so that neither a
        // lamp on a ceiling nor an emitter's own surface hides it.
        vec3 to_light = vec3(light) - shadow_origin;
        float dist = sqrt(dot(to_light, to_light));
        return !occluded(Ray(shadow_origin, to_light / dist), dist * SHADOW_RAY_END);
    }
    return true;
}
