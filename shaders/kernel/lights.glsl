// The scene's `lights` (layout.glsl, Light) seen from a point: the way toward each,
// and a spot light's cone. Shared by local shading (shade.glsl) and global mode's
// next-event estimation (global.glsl), which weigh what arrives by their own
// conventions: local mode without fall-off, global mode with 1 / r^2 for point and
// spot lights and none for a directional light.

// The vector from p toward a light: to its position, or for a directional light
// (position.w = 0) the light's own unit direction, whatever p, whose length 1 is then
// a distance that does not fall off. Without HAS_DIRECTED_LIGHTS, the point light's
// position - p, as written.
vec3 toward_light(Light light, vec3 p) {
    return vec3(light.position) - (HAS_DIRECTED_LIGHTS ? light.position.w : 1.0f) * p;
}

// What a spot light's cone lets through toward the unit direction -l (l from the
// lit point toward the light): 1 inside the inner cone, 0 outside the outer one, and
// between them t^2 with t the linear ramp in the cosine of the angle from the axis,
// (cos - cos(outer)) / (cos(inner) - cos(outer)): glTF KHR_lights_punctual's falloff.
// 1 for the other kinds (cone = (0, 0, 0, 1)). Outside the cone the light sends no
// shadow ray, so whether the point lies inside is a decision.
float cone_factor(Light light, vec3 l) {
    float t = clamp(dot(vec3(light.cone), -l) + light.cone.w, 0.0f, 1.0f);
    float factor = t * t;
    note_decision(factor > 0.0f ? DECISION_INSIDE_CONE : DECISION_OUTSIDE_CONE);
    return factor;
}
