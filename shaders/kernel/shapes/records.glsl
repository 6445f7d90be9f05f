// What every shape's file (shapes/kinds.glsl) works with: the nearest hit of a trace
// so far, and the points and light samples drawn on an emitter.

// The nearest hit so far: the primitive's reference, its distance, and what the kind
// needs to make the hit record (<name>_hit) once the trace is over.
struct Nearest {
    float t;          // the bound for further tests: t_max until something is hit
                      // (a shadow ray's sphere blocker leaves it: the trace ends there)
    uint ref;         // REF_NONE until something is hit
    vec2 uv;          // a triangle's barycentric weights u (of p1) and v (of p2)
    uint part;        // the part of a cylinder hit (CYLINDER_SIDE, _BASE_CAP, _TOP_CAP)
};

// A point drawn uniformly by area on an emitter.
struct EmitterPoint {
    vec3 position;
    vec3 normal;     // unit geometric normal on the emitting (front) side
    vec3 emission;   // radiance leaving the front face, at this point
    float weight;    // the emitter's weight: its density is weight / emitter_power()
};

// A point on the lights as seen from a point o, and the density over solid angle at
// o of having drawn the direction toward it. pdf = 0: the sample carries no light
// (o lies behind a one-sided emitter), and no shadow ray need be traced.
struct LightSample {
    vec3 position;
    vec3 normal;     // unit geometric normal on the emitting (front) side
    vec3 emission;   // radiance leaving the front face
    float pdf;
};

// The mean of an emission's channels: an emitter's power over pi times its area.
float emission_weight(vec3 emission) {
    return (emission.x + emission.y + emission.z) * (1.0f / 3.0f);
}
