// Rays, hit records and the offset that keeps secondary rays off their own surface.

struct Ray {
    vec3 origin;
    vec3 dir;   // unit length
};

struct Hit {
    float t;          // INFINITY_T when nothing was hit
    vec3 normal;      // shading normal, unit length, facing the incoming ray
    vec3 geo_normal;  // geometric normal, unit length, facing the incoming ray
    vec3 lift;        // toward the smooth surface the vertex normals describe (terminator.glsl); zero elsewhere
    uint material;
    bool front_face;  // the ray arrived on the side the primitive calls its front
    uint prim;        // what was hit, as a grid reference (kind << REF_KIND_SHIFT | index); REF_NONE for nothing
    vec2 uv;          // texture coordinates (triangles and quads with HAS_TEXTURES; 0 elsewhere)
    vec2 bary;        // a triangle's weights of p1 and p2 at the hit (vertex_data.glsl); 0 elsewhere
};

// v / |v|, by a correctly rounded sqrt and division. Not normalize(): lavapipe
// computes it as v * inversesqrt(dot(v, v)), an approximation a few ULPs off, and an
// ULP in a normal or a direction is what mirrors amplify into a differing pixel.
// With this, both backends compute bit-identical unit vectors.
vec3 unit_vector(vec3 v) {
    precise vec3 u = v / sqrt(dot(v, v));
    return u;
}

// Whether x is finite, from its exponent bits: a driver that assumes no NaN or
// infinity (without SignedZeroInfNanPreserve) may fold isnan() and isinf() to false,
// but not an integer test.
bool is_finite_bits(float x) {
    return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u;
}

// For CHECK: every channel finite and not negative (a weight, a radiance).
bool is_weight(vec3 v) {
    return is_finite_bits(v.x) && is_finite_bits(v.y) && is_finite_bits(v.z) && v.x >= 0.0f && v.y >= 0.0f &&
           v.z >= 0.0f;
}

// For CHECK: a unit vector, to float's rounding of a normalization.
bool is_unit(vec3 v) {
    return abs(dot(v, v) - 1.0f) < 1.0e-4f;
}

Hit no_hit() {
    return Hit(INFINITY_T, vec3(0.0f), vec3(0.0f), vec3(0.0f), 0u, false, REF_NONE, vec2(0.0f), vec2(0.0f));
}

// Moves a point off a surface along its geometric normal by an amount proportional to
// the point's own magnitude, in integer ULPs, so the offset is right at any scale
// (Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems ch. 6). Near the origin, where ULPs get tiny, a fixed float offset
// takes over: within 1/32 of it, by 2^-16, both times the scale 2^-offset_shrink() of
// a scene smaller than 1 (params.glsl), so that such a scene is offset as it would be
// at size 1 (decision 0053). Powers of two, built from their exponent bits: at shrink
// 0 these are 1/32 and 1/65536 exactly.
float offset_coordinate(float p, float n) {
    uint shrink = offset_shrink();
    float ORIGIN_REGION = uintBitsToFloat((122u - shrink) << 23);  // 2^-5 2^-shrink
    float FLOAT_SCALE = uintBitsToFloat((111u - shrink) << 23);    // 2^-16 2^-shrink
    const float INT_SCALE = 256.0f;
    int ulps = int(INT_SCALE * n);
    float moved = intBitsToFloat(floatBitsToInt(p) + (p < 0.0f ? -ulps : ulps));
    return abs(p) < ORIGIN_REGION ? p + FLOAT_SCALE * n : moved;
}

vec3 offset_ray_origin(vec3 p, vec3 geo_normal) {
    return vec3(offset_coordinate(p.x, geo_normal.x),
                offset_coordinate(p.y, geo_normal.y),
                offset_coordinate(p.z, geo_normal.z));
}

// Where shadow rays leave a hit at p: lifted toward the smooth surface (zero lift but
// on smooth triangles), then moved off the flat one.
vec3 shadow_ray_origin(vec3 p, Hit hit) {
    return offset_ray_origin(p + hit.lift, hit.geo_normal);
}
